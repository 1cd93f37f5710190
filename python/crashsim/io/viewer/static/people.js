/* crashsim case viewer: pedestrians and cyclists, each drawn and listed as one person.
 *
 * A person's bodies (a pedestrian's 16 segments; a cyclist's rider segments and its bicycle's
 * frame and wheels) are separate bodies of the run, posed each as any vehicle. The page data
 * marks each body with its "person" and "role" ("segment" or "bicycle"), taken from the
 * report's pedestrians[] (its bodies and bicycle.bodies): this file groups them, and builds a
 * person's panel and inputs from the report's numbers. viewer.js calls
 * window.crashsimPeople(helpers) once and uses what it returns.
 *
 * Whole-body centre of mass (for the label, the path and the speed plot; not a number shown):
 * the segments' CGs weighted by their masses, world frame, m.
 */
(function () {
  'use strict';

  window.crashsimPeople = function (h) {
    const { data, el, fmt, numCell, kvTable } = h;
    const report = data.report;
    const entries = report.pedestrians || [];

    // The persons of the page, in the order of their first body: {name, kind, index (in
    // report.pedestrians), colour, shade, segments [bodies], bicycle [bodies], members}.
    function group(bodies) {
      const out = new Map();
      for (const b of bodies) {
        if (!b.person) continue;
        if (!out.has(b.person)) {
          const index = entries.findIndex((e) => e.name === b.person);
          out.set(b.person, { name: b.person, index: index, entry: entries[index],
            kind: (entries[index] && entries[index].kind) || 'pedestrian',
            colour: null, shade: null, segments: [], bicycle: [], members: [] });
        }
        const p = out.get(b.person);
        p.members.push(b);
        if (b.role === 'bicycle') { p.bicycle.push(b); p.shade = b.colour; } else { p.segments.push(b); p.colour = p.colour || b.colour; }
      }
      return [...out.values()];
    }

    // Mass-weighted mean of the members' positions (each [x, y, z]).
    function weighted(members, position) {
      let m = 0;
      const x = [0, 0, 0];
      for (const b of members) {
        const p = position(b);
        for (let i = 0; i < 3; i++) x[i] += b.mass * p[i];
        m += b.mass;
      }
      return x.map((c) => c / m);
    }

    // The person's whole-body centre of mass as drawn now (the members' current poses; null
    // before the first pose).
    const centreNow = (p) => (p.segments.every((b) => b.current)
      ? weighted(p.segments, (b) => b.current.position) : null);

    // Per sample k: the whole-body CG (positions) and its speed (m/s), from the samples.
    function sampled(members, key) {
      const n = members[0].arrays[key].length / 3;
      const out = new Float64Array(3 * n);
      for (let k = 0; k < n; k++) {
        const c = weighted(members, (b) => b.arrays[key].subarray(3 * k, 3 * k + 3));
        out[3 * k] = c[0]; out[3 * k + 1] = c[1]; out[3 * k + 2] = c[2];
      }
      return out;
    }
    const cgPath = (p) => sampled(p.segments, 'position');
    const cgVelocity = (p) => sampled(p.segments, 'velocity');
    const frame = (p) => p.bicycle.find((b) => b.name.endsWith('/frame')) || p.bicycle[0];

    // A cell of the report's vector at path (x, y, z), each number carrying its own path.
    function vecCell(v, digits, path) {
      const td = el('td', { class: 'num' });
      td.appendChild(document.createTextNode('('));
      v.forEach((x, i) => {
        if (i) td.appendChild(document.createTextNode(', '));
        td.appendChild(el('span', { 'data-path': path + '.' + i, text: fmt(x, digits) }));
      });
      td.appendChild(document.createTextNode(')'));
      return td;
    }

    const still = (speed) => (speed < 0.1 ? ' (at rest)' : ' (still moving)');

    // Rows of one struck_by record (a person's or a bicycle's) at path base.
    function struckRows(s, base, what) {
      const rows = [
        ['first contact with ' + s.vehicle, numCell(s.first_contact_time, 4, base + '.first_contact_time'), 's'],
        ['throw distance (' + what + ')', numCell(s.throw_distance, 2, base + '.throw_distance'), 'm'],
      ];
      // a person's post-impact trajectory type (crashsim.analysis.throw.trajectory_type)
      if (s.trajectory) rows.push(['trajectory', s.trajectory, '']);
      const first = s.segments[0];
      if (first) rows.push(['first to touch', first.segment + ' at ' + fmt(first.time, 4) + ' s', '']);
      const k = s.segments.findIndex((c) => c.segment === 'head');
      if (k >= 0) {
        const c = s.segments[k], at = base + '.segments.' + k;
        rows.push(
          ['head contact time', numCell(c.time, 4, at + '.time'), 's'],
          ['head wrap-around distance', c.wrap_around === null
            ? el('td', { class: 'num', text: 'off the front and top' })
            : numCell(c.wrap_around, 2, at + '.wrap_around'), 'm'],
          ['head speed relative to ' + s.vehicle, numCell(c.relative_speed, 2, at + '.relative_speed'), 'm/s'],
          ['head peak relative speed', numCell(c.peak_relative_speed, 2, at + '.peak_relative_speed'), 'm/s'],
        );
      }
      return rows;
    }

    // A person's panel: its throw, head contact and rest, as the report gives them. A click on
    // its title brings the camera to it (focus), on a time jumps there (jump).
    function panel(p, jump, focus) {
      const sec = el('section', { class: 'person', id: 'person-' + p.name });
      const e = p.entry;
      const swatch = el('span', { class: 'swatch' });
      swatch.style.background = p.colour;
      const title = el('h3', {}, [swatch, p.name + ' (' + p.kind + ')']);
      title.style.cursor = 'pointer';
      title.title = 'bring the camera to it';
      title.addEventListener('click', () => focus(p.name));
      sec.appendChild(title);
      if (!e) {
        sec.appendChild(el('p', { class: 'muted', text: 'The report has no section for it.' }));
        return sec;
      }
      const base = 'pedestrians.' + p.index;
      const rows = [];
      if (!e.struck_by.length) rows.push(['struck by', 'no vehicle', '']);
      e.struck_by.forEach((s, j) => rows.push(...struckRows(s, base + '.struck_by.' + j, 'whole-body CG')));
      rows.push(
        ['whole-body CG at ' + fmt(e.end_time, 2) + ' s', vecCell(e.rest, 2, base + '.rest'), 'm'],
        ['its speed then' + still(e.rest_speed), numCell(e.rest_speed, 2, base + '.rest_speed'), 'm/s'],
      );
      const table = kvTable(rows);
      sec.appendChild(table);
      // a click on a time jumps there
      for (const td of table.querySelectorAll('[data-path$="time"]')) {
        td.style.cursor = 'pointer';
        td.title = 'show this moment';
        td.addEventListener('click', () => jump(Number(td.textContent)));
      }
      const b = e.bicycle;
      if (b) {
        const sw = el('span', { class: 'swatch' });
        sw.style.background = p.shade;
        sec.appendChild(el('p', { class: 'muted' }, [sw, 'its bicycle (' + fmt(b.mass, 2) + ' kg), frame and wheels:']));
        const bb = base + '.bicycle';
        const brows = [];
        if (!b.struck_by.length) brows.push(['struck by', 'no vehicle', '']);
        b.struck_by.forEach((s, j) => brows.push(...struckRows(s, bb + '.struck_by.' + j, 'frame CG')));
        brows.push(
          ['frame CG at ' + fmt(e.end_time, 2) + ' s', vecCell(b.rest, 2, bb + '.rest'), 'm'],
          ['its speed then' + still(b.rest_speed), numCell(b.rest_speed, 2, bb + '.rest_speed'), 'm/s'],
        );
        sec.appendChild(kvTable(brows));
      }
      return sec;
    }

    // The persons' inputs (the report's): kind, stature, mass, bodies, a bicycle's mass.
    function inputs(persons) {
      const table = el('table', { class: 'data' });
      table.appendChild(el('tr', {}, [el('th', { text: 'person' }), ...persons.map((p) => el('th', { text: p.name })), el('th', { text: 'unit' })]));
      const row = (label, unit, f) => table.appendChild(el('tr', {}, [el('th', { text: label }),
        ...persons.map((p) => { const c = p.entry ? f(p.entry, 'pedestrians.' + p.index) : '-'; return typeof c === 'string' ? el('td', { class: 'num', text: c }) : c; }),
        el('td', { class: 'unit', text: unit })]));
      row('kind', '', (e) => e.kind || 'pedestrian');
      row('stature', 'm', (e, b) => (e.height === undefined ? '-' : numCell(e.height, 3, b + '.height')));
      row('mass', 'kg', (e, b) => (e.mass === undefined ? '-' : numCell(e.mass, 1, b + '.mass')));
      row('bodies (segments + bicycle)', '', (e) => e.bodies.length + (e.bicycle ? ' + ' + e.bicycle.bodies.length : ''));
      row('bicycle mass', 'kg', (e, b) => (e.bicycle ? numCell(e.bicycle.mass, 2, b + '.bicycle.mass') : '-'));
      return table;
    }

    // The report's contact pairs with a person's bodies as one entry per person and set of
    // parameters: [{title, parameters}] in the report's order (the normal points from the first
    // into the second).
    function pairGroups(pairs, persons) {
      const owner = new Map();
      for (const p of persons) for (const b of p.members) owner.set(b.name, p.name);
      const short = (name) => name.slice(name.indexOf('/') + 1);
      const groups = new Map();
      for (const pair of pairs) {
        const [a, b] = pair.vehicles;
        const key = JSON.stringify([owner.get(a) || a, owner.get(b) || b, pair.parameters]);
        if (!groups.has(key)) groups.set(key, { pairs: [], parameters: pair.parameters });
        groups.get(key).pairs.push(pair.vehicles);
      }
      return [...groups.values()].map((g) => {
        const [a, b] = g.pairs[0];
        const pa = owner.get(a), pb = owner.get(b);
        if (g.pairs.length === 1) return { title: 'pair ' + a + ' \u2192 ' + b, parameters: g.parameters };
        let title;
        if (pa && pa === pb) {
          title = 'pairs within ' + pa + ': ' + g.pairs.map(([x, y]) => short(x) + ' \u2192 ' + short(y)).join(', ');
        } else {
          const list = g.pairs.map(([x, y]) => short(pb ? y : x)).join(', ');
          title = 'pairs ' + (pa || a) + ' \u2192 ' + (pb || b) + ' (' + g.pairs.length + ' bodies: ' + list + ')';
        }
        return { title: title, parameters: g.parameters };
      });
    }

    return { group, centreNow, cgPath, cgVelocity, frame, panel, inputs, pairGroups };
  };
})();
