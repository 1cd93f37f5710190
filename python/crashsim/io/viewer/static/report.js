/* crashsim case viewer: the report panel beside the 3-D scene (its impacts, the pedestrians
 * and cyclists, each vehicle's and person's speed over the run, the scene's inputs).
 *
 * Every number is the report's own (data.report: crashsim.report(result).to_dict()), each
 * number cell carrying the report path it shows (data-path). viewer.js calls
 * window.crashsimReport(helpers) once, after it has built the bodies and persons, and calls
 * build() on what it returns; the plots' time cursors are pushed onto helpers.cursors, which
 * viewer.js moves with the time.
 */
(function () {
  'use strict';

  window.crashsimReport = function (h) {
    const { data, el, fmt, fmtVec, numCell, kvTable, norm, qNormalize, qRotate, niceStep,
      KMH, MPH, samples, T0, T1, cursors, bodies, persons, people, setTime, focusOn } = h;

    function impactSection(imp, i) {
      const base = 'impacts.' + i;
      const sec = el('section', { class: 'impact', id: 'impact-' + imp.number });
      const title = 'Impact ' + imp.number + ': ' + imp.vehicles[0] + ' (1) \u2192 ' + imp.vehicles[1] + ' (2), ' +
        imp.impact_type + (imp.secondary ? ', secondary' : '');
      const h = el('h3', { text: title });
      h.style.cursor = 'pointer';
      h.title = 'show the exchange';
      h.addEventListener('click', () => setTime(imp.exchange_time));
      sec.appendChild(h);
      const dtp = imp.depth_of_penetration;
      sec.appendChild(kvTable([
        ['first overlap t0', numCell(imp.first_contact_time, 6, base + '.first_contact_time'), 's'],
        ['exchange t', numCell(imp.exchange_time, 6, base + '.exchange_time'), 's'],
        ['depth of penetration (' + dtp.mode + ')', numCell(dtp.value * 1000, 3), 'ms'],
        ['centroid (world)', fmtVec(imp.centroid.world, 4), 'm'],
        ['normal 1 \u2192 2', fmtVec(imp.normal, 4), ''],
        ['impulse on ' + imp.vehicles[1], fmtVec(imp.impulse.on_vehicle_2, 1), 'N s'],
        ['|impulse|', numCell(imp.impulse.magnitude, 1, base + '.impulse.magnitude'), 'N s'],
        ['closing speed', numCell(imp.closing_speed, 3, base + '.closing_speed'), 'm/s'],
        ['energy dissipated', numCell(imp.energy.dissipated, 1, base + '.energy.dissipated'), 'J'],
        ['overlap depth along n', numCell(imp.overlap.depth_along_normal, 4, base + '.overlap.depth_along_normal'), 'm'],
        ['overlap width', numCell(imp.overlap.width, 4, base + '.overlap.width'), 'm'],
        // every figure of the impact as the report lists it (ImpactReport.figures)
        ...(imp.figures || []).map((f, k) =>
          [f.label, numCell(f.value, f.digits, base + '.figures.' + k + '.value'), f.unit]),
      ]));
      const parties = imp.parties;
      const table = el('table', { class: 'data per-vehicle' });
      table.appendChild(el('tr', {}, [el('th', { text: 'per vehicle' }),
        ...parties.map((p) => el('th', { text: p.name + ' (' + p.role + ')' })), el('th', { text: 'unit' })]));
      const row = (label, unit, cells) => table.appendChild(
        el('tr', {}, [el('th', { text: label }), ...cells, el('td', { class: 'unit', text: unit })]));
      const P = (j, key) => base + '.parties.' + j + '.' + key;
      const get = (obj, key) => key.split('.').reduce((o, k) => (o === null || o === undefined ? o : o[k]), obj);
      const numbers = (label, unit, key, digits) => row(label, unit,
        parties.map((p, j) => numCell(get(p, key), digits, P(j, key))));
      numbers('|\u0394V|', 'm/s', 'delta_v.magnitude', 3);
      row('|\u0394V|', 'km/h', parties.map((p) => numCell(p.delta_v.magnitude * KMH, 2)));
      row('|\u0394V|', 'mph', parties.map((p) => numCell(p.delta_v.magnitude * MPH, 2)));
      row('\u0394V world (x, y, z)', 'm/s', parties.map((p) => el('td', { class: 'num', text: fmtVec(p.delta_v.world, 3) })));
      numbers('\u0394V longitudinal (EDR, +forward)', 'm/s', 'delta_v.longitudinal', 3);
      numbers('\u0394V lateral (EDR, +right)', 'm/s', 'delta_v.lateral', 3);
      row('PDOF', 'deg', parties.map((p, j) => numCell(p.pdof_deg, 2, P(j, 'pdof_deg'))));
      row('clock', "o'clock", parties.map((p, j) => el('td', { class: 'num', text: p.clock === null ? 'unknown' : String(p.clock), 'data-path': P(j, 'clock') })));
      numbers('yaw-rate change', 'deg/s', 'yaw_rate_change_deg_s', 2);
      numbers('speed before', 'm/s', 'speed_before', 3);
      numbers('speed after', 'm/s', 'speed_after', 3);
      row('struck face', '', parties.map((p) => el('td', { class: 'num', text: p.struck_face })));
      numbers('effective mass along n', 'kg', 'effective_mass', 1);
      numbers('energy share', 'J', 'energy.share', 1);
      numbers('EES', 'm/s', 'energy.ees', 3);
      numbers('crush: bounding box', 'm', 'deformation.bounding_box', 4);
      row('crush: mesh', 'm', parties.map((p, j) => {
        const td = numCell(p.deformation.mesh, 4, P(j, 'deformation.mesh'));
        if (p.deformation.mesh === null) td.textContent = 'n/a';
        return td;
      }));
      numbers('overlap depth', 'm', 'deformation.overlap_depth', 4);
      numbers('C max (spring model)', 'm', 'deformation.spring_model.max_crush', 4);
      numbers('C residual (SAE 880223)', 'm', 'deformation.spring_model.residual_crush', 4);
      sec.appendChild(table);
      if (imp.obstacle) {
        sec.appendChild(el('p', { class: 'muted', text: imp.obstacle.name + ' is a fixed obstacle (infinite mass, no \u0394V); struck on its ' + (imp.obstacle.struck_side || imp.obstacle.struck_face) + ' side (its frame).' }));
      }
      const notes = [...imp.notes];
      for (const p of parties) for (const n of p.deformation.notes) notes.push(p.name + ': ' + n);
      if (notes.length) sec.appendChild(el('ul', { class: 'notes' }, notes.map((n) => el('li', { text: n }))));
      return sec;
    }

    // Speeds over the run (an inline SVG) of a vehicle's CG, or a person's (lines: {velocity (3
    // per sample), colour}), with the exchanges of the bodies `names` and a cursor.
    function speedPlot(name, lines, names) {
      const NS = 'http://www.w3.org/2000/svg';
      const svg = document.createElementNS(NS, 'svg');
      svg.setAttribute('class', 'plot');
      svg.setAttribute('viewBox', '0 0 600 170');
      svg.setAttribute('data-vehicle', name);
      const T = samples.t;
      const speeds = lines.map((line) => {
        const V = line.velocity, speed = new Float64Array(T.length);
        for (let k = 0; k < T.length; k++) speed[k] = Math.hypot(V[3 * k], V[3 * k + 1], V[3 * k + 2]);
        return speed;
      });
      const vmax = Math.max(1e-3, ...speeds.map((s) => s.reduce((a, b) => Math.max(a, b), 0)));
      const step = niceStep(vmax, 4), top = Math.ceil(vmax / step) * step;
      const L = 44, R = 590, Tp = 10, B = 145;
      const x = (t) => L + ((t - T0()) / (T1() - T0() || 1)) * (R - L);
      const y = (v) => B - (v / top) * (B - Tp);
      const add = (tag, attrs, text) => {
        const e = document.createElementNS(NS, tag);
        for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
        if (text !== undefined) e.textContent = text;
        svg.appendChild(e);
        return e;
      };
      for (let v = 0; v <= top + 1e-9; v += step) {
        add('line', { x1: L, x2: R, y1: y(v), y2: y(v), stroke: '#e2e2e2' });
        add('text', { x: L - 4, y: y(v) + 3, 'text-anchor': 'end' }, String(+v.toFixed(6)));
      }
      const tstep = niceStep(T1() - T0() || 1, 6);
      for (let t = Math.ceil(T0() / tstep) * tstep; t <= T1() + 1e-12; t += tstep) {
        add('line', { x1: x(t), x2: x(t), y1: Tp, y2: B, stroke: '#eeeeee' });
        add('text', { x: x(t), y: B + 12, 'text-anchor': 'middle' }, String(+t.toFixed(6)));
      }
      for (const i of data.impacts) {
        if (!i.vehicles.some((v) => names.includes(v))) continue;
        add('line', { x1: x(i.time), x2: x(i.time), y1: Tp, y2: B, stroke: '#000', 'stroke-dasharray': '3 2' });
        add('text', { x: x(i.time) + 3, y: Tp + 9 }, String(i.number));
      }
      speeds.forEach((speed, j) => {
        let d = '';
        for (let k = 0; k < T.length; k++) d += (k ? 'L' : 'M') + x(T[k]).toFixed(2) + ' ' + y(speed[k]).toFixed(2);
        add('path', { d: d, fill: 'none', stroke: lines[j].colour, 'stroke-width': 1.6 });
      });
      add('line', { x1: L, x2: R, y1: B, y2: B, stroke: '#333' });
      add('line', { x1: L, x2: L, y1: Tp, y2: B, stroke: '#333' });
      add('text', { x: R, y: B + 24, 'text-anchor': 'end' }, 't (s)');
      add('text', { x: 4, y: Tp + 2, 'dominant-baseline': 'hanging' }, 'm/s');
      const cursor = add('line', { x1: L, x2: L, y1: Tp, y2: B, stroke: '#c00' });
      cursors.push((t) => { cursor.setAttribute('x1', x(t)); cursor.setAttribute('x2', x(t)); });
      svg.addEventListener('click', (e) => {
        const box = svg.getBoundingClientRect();
        const px = ((e.clientX - box.left) / box.width) * 600;
        setTime(T0() + ((px - L) / (R - L)) * (T1() - T0()));
      });
      return svg;
    }

    const PARAMETERS = {  // contact parameters: label, unit, conversion from SI
      depth_of_penetration: ['depth of penetration', 'ms', (v) => (typeof v === 'number' ? fmt(v * 1000, 3) : String(v))],
      restitution: ['restitution', '', (v) => fmt(v, 3)],
      friction: ['inter-vehicle friction', '', (v) => fmt(v, 3)],
      restitution_mode: ['restitution mode', '', String],
      normal: ['normal', '', (v) => (v === null ? 'automatic' : JSON.stringify(v))],
      pitch: ['contact-plane pitch', 'deg', (v) => fmt((v * 180) / Math.PI, 2)],
      centroid: ['centroid', '', (v) => (v === null ? 'automatic' : JSON.stringify(v))],
    };

    function parameterRows(params) {
      return Object.entries(params).map(([k, v]) => {
        const [label, unit, f] = PARAMETERS[k] || [k, '', (x) => (typeof x === 'number' ? String(x) : JSON.stringify(x))];
        return [label, f(v), unit];
      });
    }

    function inputsSection(report) {
      const sec = el('section', { id: 'inputs' });
      sec.appendChild(el('h2', { text: 'Scene inputs' }));
      // a person's bodies are listed as the person (below), not as vehicles
      const vs = report.scene.vehicles.filter((v) => !persons.some((p) => p.members.some((b) => b.name === v.name)));
      const table = el('table', { class: 'data' });
      table.appendChild(el('tr', {}, [el('th', { text: 'vehicle' }), ...vs.map((v) => el('th', { text: v.name })), el('th', { text: 'unit' })]));
      const row = (label, unit, f) => table.appendChild(el('tr', {}, [el('th', { text: label }),
        ...vs.map((v, j) => { const c = f(v, j); return typeof c === 'string' ? el('td', { class: 'num', text: c }) : c; }),
        el('td', { class: 'unit', text: unit })]));
      const path = (j, key) => 'scene.vehicles.' + report.scene.vehicles.indexOf(vs[j]) + '.' + key;
      row('mass', 'kg', (v, j) => numCell(v.mass, 1, path(j, 'mass')));
      row('mass from', '', (v) => v.mass_source);
      row('length x width x height', 'm', (v) => {
        const b = v.mesh.bounds_model;
        return [0, 1, 2].map((i) => fmt(b[1][i] - b[0][i], 2)).join(' x ');
      });
      row('triangles (mesh / drawn)', '', (v) => {
        const body = bodies.find((b) => b.name === v.name);
        return v.mesh.triangles + ' / ' + (body ? body.mesh.triangles : '-');
      });
      row('CG (model frame)', 'm', (v) => fmtVec(v.cg_model, 3));
      row('Ixx, Iyy, Izz', 'kg m\u00B2', (v) => fmtVec([v.inertia[0][0], v.inertia[1][1], v.inertia[2][2]], 1));
      const speed = (v) => norm(v.initial_state.velocity);
      row('initial speed', 'm/s', (v, j) => numCell(speed(v), 3));
      row('initial speed', 'km/h', (v) => fmt(speed(v) * KMH, 2));
      row('initial speed', 'mph', (v) => fmt(speed(v) * MPH, 2));
      row('initial heading', 'deg', (v) => {
        const q = qNormalize(v.initial_state.orientation);
        const x = qRotate(q, [1, 0, 0]);
        return fmt((Math.atan2(x[1], x[0]) * 180) / Math.PI, 2);
      });
      row('initial yaw rate', 'deg/s', (v) => fmt((v.initial_state.angular_velocity[2] * 180) / Math.PI, 2));
      row('initial CG position', 'm', (v) => fmtVec(v.initial_state.position, 3));
      for (const face of ['front', 'rear', 'left', 'right']) {
        row('stiffness ' + face + ' A, B', 'N/m, N/m\u00B2', (v) => {
          const s = v.stiffness && v.stiffness[face];
          return s ? fmt(s.A, 0) + ', ' + fmt(s.B, 0) : 'no data';
        });
      }
      // a run on the ground: the wheels, steering and tyre as the engine ran them (the report's
      // scene.vehicles[].wheels)
      if (vs.some((v) => v.wheels)) {
        const w = (f) => (v) => (v.wheels ? f(v.wheels) : '-');
        const DEG = 180 / Math.PI;
        row('tyre', '', w((x) => {
          const t = x.tyre;
          if (t.model === 'linear') return 'linear, 1 per ' + fmt(1 / (t.cornering / DEG), 1) + ' deg';
          if (t.model === 'linear_friction_scaled') return 'mu Fz at ' + fmt(t.saturation_angle * DEG, 1) + ' deg';
          return 'Magic Formula ' + [t.b, t.c, t.e].map((c) => fmt(c, 2)).join(', ');
        }));
        row('combined slip', '', w((x) => x.tyre.combined.replace('_', ' ')));
        row('rolling resistance', '', w((x) => fmt(x.tyre.rolling_resistance, 3)));
        row('steering ratio, Ackermann', '', w((x) => (x.steering.ratio === null ? 'none' : fmt(x.steering.ratio, 1)) +
          ', ' + fmt(x.steering.ackermann, 2) + ' (' + x.steering.reference + ')'));
        row('springs', 'Hz', w((x) => x.natural_frequencies.map((f) => fmt(f, 2)).join(', ')));
        row('damping ratios', '', w((x) => x.damping_ratios.map((f) => fmt(f, 2)).join(', ')));
        row('roll stiffness front, rear', 'N m/deg', w((x) => (x.roll_stiffness
          ? fmt(x.roll_stiffness.front / DEG, 0) + ', ' + fmt(x.roll_stiffness.rear / DEG, 0) : '-')));
        row('roll gradient', 'deg/g', w((x) => (x.roll_gradient === undefined || x.roll_gradient === null ? '-' : fmt(x.roll_gradient * DEG, 1))));
        row('ABS', '', w((x) => (x.abs ? 'on' : 'off')));
      }
      sec.appendChild(table);
      if (persons.length) {
        sec.appendChild(el('h3', { text: 'Pedestrians and cyclists' }));
        sec.appendChild(people.inputs(persons));
      }
      if (report.scene.obstacles && report.scene.obstacles.length) {
        sec.appendChild(el('h3', { text: 'Fixed obstacles' }));
        sec.appendChild(kvTable(report.scene.obstacles.map((o) => [o.name + ' (' + o.kind + ')',
          'extents ' + fmtVec(o.extents, 2) + ' at ' + fmtVec(o.position, 2), 'm'])));
      }
      sec.appendChild(el('h3', { text: 'Contact parameters' }));
      sec.appendChild(el('p', { class: 'muted', text: 'defaults (every pair unless overridden):' }));
      sec.appendChild(kvTable(parameterRows(report.scene.contact.defaults)));
      for (const g of people.pairGroups(report.scene.contact.pairs, persons)) {
        sec.appendChild(el('p', { class: 'muted', text: g.title + ' (the normal points from the first into the second):' }));
        sec.appendChild(kvTable(parameterRows(g.parameters)));
      }
      const g = data.ground;
      sec.appendChild(el('h3', { text: 'Run' }));
      const run = report.run;
      sec.appendChild(kvTable([
        ['duration', numCell(run.duration, 4, 'run.duration'), 's'],
        ['largest step dt', numCell(run.dt === null ? null : run.dt * 1000, 3), 'ms'],
        ['samples (run / on this page)', run.samples + ' / ' + data.samples.kept, ''],
        ['ground', g.modelled ? ('modelled, z = ' + fmt(g.height, 3) + (g.friction !== null && g.friction !== undefined ? ', friction ' + fmt(g.friction, 2) : '')) : 'not modelled (drawn at z = 0)', g.modelled ? 'm' : ''],
        ['motion between samples', data.interpolation, ''],
      ]));
      return sec;
    }

    function buildReport() {
      const report = data.report;
      const aside = document.getElementById('report');
      aside.appendChild(el('h2', { text: 'Report' }));
      aside.appendChild(el('p', { class: 'muted', text: 'crashsim ' + report.crashsim_version +
        ', schema ' + report.schema + ' ' + report.schema_version + '. The numbers are the report\'s (crashsim.report(result).to_dict()). ' +
        'EDR axes: longitudinal +forward, lateral +right; PDOF: the direction the force comes from, clockwise from ahead.' }));
      if (!report.impacts.length) aside.appendChild(el('p', { text: 'No impulse exchange in this run.' }));
      report.impacts.forEach((imp, i) => aside.appendChild(impactSection(imp, i)));
      if (persons.length) {
        aside.appendChild(el('h2', { text: 'Pedestrians and cyclists' }));
        aside.appendChild(el('p', { class: 'muted', text: 'The report\'s pedestrians[] section: each person\'s bodies drawn ' +
          'as one. Throw distance: the horizontal travel of the centre of mass from the vehicle\'s first contact to the end ' +
          'of the run; head contact: the first overlap of the head with the vehicle, its wrap-around distance and speed relative to it.' }));
        for (const p of persons) aside.appendChild(people.panel(p, setTime, (name) => focusOn(name)));
      }
      aside.appendChild(el('h2', { text: 'Speed of each vehicle' }));
      for (const b of bodies) {
        if (b.kind === 'obstacle' || b.person) continue;
        aside.appendChild(el('h3', { text: b.name + ': speed of the CG (m/s; dashed: its exchanges, red: now)' }));
        aside.appendChild(speedPlot(b.name, [{ velocity: b.arrays.velocity, colour: b.colour }], [b.name]));
      }
      for (const p of persons) {
        const lines = [{ velocity: people.cgVelocity(p), colour: p.colour }];
        if (p.bicycle.length) lines.push({ velocity: people.frame(p).arrays.velocity, colour: p.shade });
        aside.appendChild(el('h3', { text: p.name + ': speed of the whole-body CG' + (p.bicycle.length
          ? ' and (darker) of the bicycle\'s frame' : '') + ' (m/s; dashed: its exchanges, red: now)' }));
        aside.appendChild(speedPlot(p.name, lines, p.members.map((b) => b.name)));
      }
      aside.appendChild(inputsSection(report));
    }

    return { build: buildReport };
  };
})();
