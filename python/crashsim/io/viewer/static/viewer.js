/* crashsim case viewer: the 3-D scene, the timeline and the report of one run.
 *
 * Everything the page shows comes from the JSON block "crashsim-data" (written by
 * crashsim.io.viewer). Numbers in the tables are the report's own; poses are the run's samples
 * interpolated exactly as crashsim's Result.state does (torque-free motion from the last
 * sample, or Hermite/slerp between samples for runs on the ground). World frame: z up, SI.
 * Quaternions are crashsim's (w, x, y, z); three.js takes (x, y, z, w).
 *
 * For tests and tools the page exposes window.crashsim: ready, error, time(), setTime(t),
 * state(name, t), poses(), firstDrawMs.
 */
(function () {
  'use strict';

  const api = { ready: false, error: null, firstDrawMs: null, frames: 0 };
  window.crashsim = api;
  const data = JSON.parse(document.getElementById('crashsim-data').textContent);

  // ---------------------------------------------------------------- packed arrays

  const TYPES = { f8: Float64Array, f4: Float32Array, u2: Uint16Array, u4: Uint32Array, u1: Uint8Array };

  function base64Bytes(text) {
    const bin = atob(text);
    const out = new Uint8Array(bin.length);
    for (let i = 0; i < bin.length; i++) out[i] = bin.charCodeAt(i);
    return out;
  }

  // A packed array {dtype, count, b64}: base64 of zlib-deflated little-endian bytes.
  async function unpack(packed) {
    const stream = new Blob([base64Bytes(packed.b64)]).stream()
      .pipeThrough(new DecompressionStream('deflate'));
    const buffer = await new Response(stream).arrayBuffer();
    const array = new TYPES[packed.dtype](buffer);
    if (array.length !== packed.count) throw new Error('packed array: wrong length');
    return array;
  }

  // ---------------------------------------------------------------- small vector maths

  const add = (a, b) => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
  const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
  const scale = (a, s) => [a[0] * s, a[1] * s, a[2] * s];
  const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const norm = (a) => Math.sqrt(dot(a, a));
  const matVec = (m, v) => [  // m: 9 numbers, row-major
    m[0] * v[0] + m[1] * v[1] + m[2] * v[2],
    m[3] * v[0] + m[4] * v[1] + m[5] * v[2],
    m[6] * v[0] + m[7] * v[1] + m[8] * v[2],
  ];

  function qMul(a, b) {  // Hamilton product, (w, x, y, z)
    return [
      a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
      a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
      a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
      a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
    ];
  }
  function qNormalize(q) {
    const n = Math.hypot(q[0], q[1], q[2], q[3]);
    return [q[0] / n, q[1] / n, q[2] / n, q[3] / n];
  }
  function qRotate(q, v) {  // R(q) v for a unit q
    const r = qMul(qMul(q, [0, v[0], v[1], v[2]]), [q[0], -q[1], -q[2], -q[3]]);
    return [r[1], r[2], r[3]];
  }
  const qRotateInv = (q, v) => qRotate([q[0], -q[1], -q[2], -q[3]], v);
  const qAxpy = (q, k, h) => [q[0] + k[0] * h, q[1] + k[1] * h, q[2] + k[2] * h, q[3] + k[3] * h];

  // ---------------------------------------------------------------- motion between samples

  const MAX_SUBSTEP_ANGLE = 0.01;  // rad per RK4 sub-step, as the engine (body.rs)

  // dq/dt = 1/2 (0, w) q with w = R I^-1 R^T L (raw 4-vector, as the engine).
  function quaternionRate(q, L, invI) {
    const u = qNormalize(q);
    const w = qRotate(u, matVec(invI, qRotateInv(u, L)));
    const r = qMul([0, w[0], w[1], w[2]], q);
    return [r[0] * 0.5, r[1] * 0.5, r[2] * 0.5, r[3] * 0.5];
  }

  function rk4Step(q, L, invI, h) {
    const k1 = quaternionRate(q, L, invI);
    const k2 = quaternionRate(qAxpy(q, k1, 0.5 * h), L, invI);
    const k3 = quaternionRate(qAxpy(q, k2, 0.5 * h), L, invI);
    const k4 = quaternionRate(qAxpy(q, k3, h), L, invI);
    const s = h / 6;
    return qNormalize([
      q[0] + (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0]) * s,
      q[1] + (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1]) * s,
      q[2] + (k1[2] + 2 * k2[2] + 2 * k3[2] + k4[2]) * s,
      q[3] + (k1[3] + 2 * k2[3] + 2 * k3[3] + k4[3]) * s,
    ]);
  }

  // Torque-free motion over dt from a state (the engine's RigidBody::advance).
  function torqueFree(body, s, dt) {
    const q0 = qNormalize(s.orientation);
    // world angular momentum L = R I R^T w (constant between impulses)
    const L = qRotate(q0, matVec(body.inertia, qRotateInv(q0, s.angular_velocity)));
    const position = add(s.position, scale(s.velocity, dt));
    let q = s.orientation;
    const wmax = norm(L) / body.min_principal;
    if (wmax > 0 && dt !== 0) {
      const n = Math.max(1, Math.ceil((wmax * Math.abs(dt)) / MAX_SUBSTEP_ANGLE));
      const h = dt / n;
      q = qNormalize(q0);
      for (let i = 0; i < n; i++) q = rk4Step(q, L, body.inverse_inertia, h);
    }
    const qu = qNormalize(q);
    const w = qRotate(qu, matVec(body.inverse_inertia, qRotateInv(qu, L)));
    return { position: position, orientation: q, velocity: s.velocity.slice(), angular_velocity: w };
  }

  function slerp(q0, q1, s) {  // shortest arc, as crashsim.result._slerp
    q0 = qNormalize(q0); q1 = qNormalize(q1);
    let d = q0[0] * q1[0] + q0[1] * q1[1] + q0[2] * q1[2] + q0[3] * q1[3];
    if (d < 0) { q1 = q1.map((x) => -x); d = -d; }
    if (d > 1 - 1e-12) return qNormalize(qAxpy(q0, sub4(q1, q0), s));
    const theta = Math.acos(Math.min(1, d));
    const a = Math.sin((1 - s) * theta), b = Math.sin(s * theta), c = Math.sin(theta);
    return [0, 1, 2, 3].map((i) => (a * q0[i] + b * q1[i]) / c);
  }
  const sub4 = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2], a[3] - b[3]];

  // Between samples k and k + 1 on the ground: Hermite position, slerp orientation.
  function hermite(body, k, t) {
    const T = samples.t;
    const t0 = T[k], t1 = T[k + 1], h = t1 - t0, s = (t - t0) / h;
    const h00 = 2 * s ** 3 - 3 * s ** 2 + 1, h10 = s ** 3 - 2 * s ** 2 + s;
    const h01 = -2 * s ** 3 + 3 * s ** 2, h11 = s ** 3 - s ** 2;
    const a = sampleOf(body, k), b = sampleOf(body, k + 1);
    const lerp = (u, v) => [0, 1, 2].map((i) => (1 - s) * u[i] + s * v[i]);
    return {
      position: [0, 1, 2].map((i) => h00 * a.position[i] + h10 * h * a.velocity[i]
        + h01 * b.position[i] + h11 * h * b.velocity[i]),
      orientation: slerp(a.orientation, b.orientation, s),
      velocity: lerp(a.velocity, b.velocity),
      angular_velocity: lerp(a.angular_velocity, b.angular_velocity),
    };
  }

  const samples = { t: null };

  function sampleOf(body, k) {
    const s = body.arrays;
    return {
      position: Array.from(s.position.subarray(3 * k, 3 * k + 3)),
      orientation: Array.from(s.orientation.subarray(4 * k, 4 * k + 4)),
      velocity: Array.from(s.velocity.subarray(3 * k, 3 * k + 3)),
      angular_velocity: Array.from(s.angular_velocity.subarray(3 * k, 3 * k + 3)),
    };
  }

  // The last sample index k with t[k] <= t (numpy's searchsorted(side="right") - 1).
  function lastSampleAtOrBefore(t) {
    const T = samples.t;
    let lo = 0, hi = T.length;
    while (lo < hi) {
      const mid = (lo + hi) >> 1;
      if (T[mid] <= t) lo = mid + 1; else hi = mid;
    }
    return Math.max(0, lo - 1);
  }

  // A body's state at time t, as Result.state gives it.
  function stateAt(body, t) {
    const T = samples.t;
    t = Math.min(Math.max(t, T[0]), T[T.length - 1]);
    const k = lastSampleAtOrBefore(t);
    const s = sampleOf(body, k);
    if (T[k] === t || body.kind === 'obstacle') return s;
    if (data.interpolation === 'hermite') return hermite(body, k, t);
    return torqueFree(body, s, t - T[k]);
  }

  // ---------------------------------------------------------------- formatting

  function fmt(x, digits) {  // as the text report: "unknown" for null, no "-0.000"
    if (x === null || x === undefined) return 'unknown';
    let text = Number(x).toFixed(digits);
    if (text.startsWith('-') && Number(text) === 0) text = text.slice(1);
    return text;
  }
  const fmtVec = (v, d) => '(' + v.map((x) => fmt(x, d)).join(', ') + ')';
  const KMH = 3.6, MPH = 1 / 0.44704;

  function el(tag, attrs, children) {
    const e = document.createElement(tag);
    for (const [k, v] of Object.entries(attrs || {})) {
      if (k === 'text') e.textContent = v; else e.setAttribute(k, v);
    }
    for (const c of children || []) e.appendChild(typeof c === 'string' ? document.createTextNode(c) : c);
    return e;
  }

  // A number cell carrying the report path it shows (for readers and tests).
  function numCell(value, digits, path) {
    const td = el('td', { class: 'num', text: fmt(value, digits) });
    if (path) td.setAttribute('data-path', path);
    return td;
  }

  function kvTable(rows) {
    const table = el('table', { class: 'data' });
    for (const [label, value, unit, path] of rows) {
      const td = typeof value === 'string' ? el('td', { class: 'num', text: value }) : value;
      if (path && td.getAttribute && !td.getAttribute('data-path')) td.setAttribute('data-path', path);
      table.appendChild(el('tr', {}, [el('th', { text: label }), td, el('td', { class: 'unit', text: unit })]));
    }
    return table;
  }

  // ---------------------------------------------------------------- the 3-D scene

  let renderer, scene, camera, controls;
  const bodies = [];           // {name, kind, colour, object, ...dynamics, arrays, person, role}
  let people, persons = [];    // people.js's helpers; the pedestrians and cyclists (one each)
  const overlays = [];         // per impact: {impact, group, labels}
  const labels = [];           // HTML labels: {div, point() -> [x,y,z] | null, visible() -> bool}
  let pathsGroup;
  let bounds = null;           // {lo, hi} of everything drawn (m)
  let currentTime = 0;

  function toThreeQuaternion(q) {
    const u = qNormalize(q);
    return new THREE.Quaternion(u[1], u[2], u[3], u[0]);
  }

  function grow(p) {
    if (!bounds) bounds = { lo: p.slice(), hi: p.slice() };
    for (let i = 0; i < 3; i++) {
      bounds.lo[i] = Math.min(bounds.lo[i], p[i]);
      bounds.hi[i] = Math.max(bounds.hi[i], p[i]);
    }
  }

  // A packed mesh as a BufferGeometry (positions = lo + step * q).
  async function meshGeometry(packed) {
    const q = await unpack(packed.positions);
    const index = await unpack(packed.indices);
    const pos = new Float32Array(q.length);
    for (let i = 0; i < q.length; i++) pos[i] = packed.lo[i % 3] + packed.step[i % 3] * q[i];
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(pos, 3));
    g.setIndex(new THREE.BufferAttribute(index, 1));
    g.computeBoundingSphere();
    return g;
  }

  // An arrow from tail along vec (m), drawn as a cylinder and a cone.
  function arrow(tail, vec, colour, radius) {
    const length = norm(vec);
    const group = new THREE.Group();
    if (!(length > 1e-9)) return group;
    const head = Math.min(length * 0.35, radius * 6);
    const material = new THREE.MeshBasicMaterial({ color: colour });
    const shaft = new THREE.Mesh(new THREE.CylinderGeometry(radius, radius, length - head, 12), material);
    shaft.position.y = (length - head) / 2;
    const cone = new THREE.Mesh(new THREE.ConeGeometry(radius * 2.5, head, 16), material);
    cone.position.y = length - head / 2;
    group.add(shaft, cone);
    // cylinders stand along +y: turn +y onto the arrow's direction
    group.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0),
      new THREE.Vector3(vec[0] / length, vec[1] / length, vec[2] / length));
    group.position.set(tail[0], tail[1], tail[2]);
    return group;
  }

  function addLabel(text, point, visible, cls) {
    const div = el('div', { class: 'label' + (cls ? ' ' + cls : ''), text: text });
    document.getElementById('labels').appendChild(div);
    labels.push({ div: div, point: point, visible: visible || (() => true) });
  }

  function niceStep(span, target) {  // grid spacing: 1, 2, 5 x 10^k
    const raw = span / target, e = Math.pow(10, Math.floor(Math.log10(raw)));
    for (const m of [1, 2, 5, 10]) if (m * e >= raw) return m * e;
    return 10 * e;
  }

  async function buildGround() {
    const g = data.ground;
    const z = g.height;
    const margin = 3;
    const lo = [bounds.lo[0] - margin, bounds.lo[1] - margin];
    const hi = [bounds.hi[0] + margin, bounds.hi[1] + margin];
    const size = Math.max(hi[0] - lo[0], hi[1] - lo[1]);
    const cx = (lo[0] + hi[0]) / 2, cy = (lo[1] + hi[1]) / 2;
    if (g.terrain) {
      const geometry = await meshGeometry(g.terrain);
      const m = new THREE.Mesh(geometry, new THREE.MeshPhongMaterial({
        color: 0xa9aaa4, flatShading: true, side: THREE.DoubleSide, shininess: 0 }));
      scene.add(m);
    } else {
      const plane = new THREE.Mesh(new THREE.PlaneGeometry(size, size),
        new THREE.MeshLambertMaterial({ color: 0xc9cbc4, side: THREE.DoubleSide }));
      plane.position.set(cx, cy, z - 0.005);
      scene.add(plane);
    }
    const step = niceStep(size, 30);
    const cells = Math.ceil(size / step);
    const grid = new THREE.GridHelper(cells * step, cells, 0x8a8c86, 0xaeb0a9);
    grid.rotation.x = Math.PI / 2;  // GridHelper lies in x-z: turn it into x-y
    grid.position.set(Math.round(cx / step) * step, Math.round(cy / step) * step, z - 0.003);
    scene.add(grid);
    api.gridStep = step;
    // friction zones: translucent polygons, blue for slippery to amber for grippy
    for (const zone of g.zones) {
      const shape = new THREE.Shape(zone.polygon.map((p) => new THREE.Vector2(p[0], p[1])));
      const c = new THREE.Color().setHSL(0.6 - 0.5 * Math.min(1, zone.friction), 0.6, 0.55);
      const m = new THREE.Mesh(new THREE.ShapeGeometry(shape), new THREE.MeshBasicMaterial({
        color: c, transparent: true, opacity: 0.45, side: THREE.DoubleSide, depthWrite: false }));
      m.position.z = z + 0.002;
      scene.add(m);
      const centre = zone.polygon.reduce((a, p) => [a[0] + p[0], a[1] + p[1]], [0, 0])
        .map((x) => x / zone.polygon.length);
      addLabel(zone.label + ': friction ' + fmt(zone.friction, 2), () => [centre[0], centre[1], z], null, 'small');
    }
    return step;
  }

  async function buildBodies() {
    samples.t = await unpack(data.samples.t);
    for (const b of data.bodies) {
      const body = Object.assign({}, b);
      body.arrays = {};
      for (const key of ['position', 'orientation', 'velocity', 'angular_velocity']) {
        body.arrays[key] = await unpack(b.samples[key]);
      }
      const geometry = await meshGeometry(b.mesh);
      const material = new THREE.MeshPhongMaterial({ color: b.colour, flatShading: true,
        side: THREE.DoubleSide, shininess: 20 });
      body.object = new THREE.Mesh(geometry, material);
      scene.add(body.object);
      body.geometry = geometry;
      // the run's reach: every sample's position plus the mesh's radius
      const r = geometry.boundingSphere.radius + norm([geometry.boundingSphere.center.x,
        geometry.boundingSphere.center.y, geometry.boundingSphere.center.z]);
      const P = body.arrays.position;
      for (let k = 0; k < P.length; k += 3) {
        grow([P[k] - r, P[k + 1] - r, P[k + 2]]);
        grow([P[k] + r, P[k + 1] + r, P[k + 2]]);
      }
      body.radius = r;
      bodies.push(body);
      if (b.person) continue;  // one label per person (below)
      addLabel(b.name, () => {
        const s = stateAt(body, currentTime).position;
        return [s[0], s[1], s[2] + (b.kind === 'obstacle' ? r * 0.6 : 1.2)];
      }, null, b.kind === 'obstacle' ? 'small' : '');
    }
  }

  // The pedestrians and cyclists: one label each, at its whole-body CG.
  function buildPersons() {
    people = window.crashsimPeople({ data: data, el: el, fmt: fmt, numCell: numCell, kvTable: kvTable });
    persons = people.group(bodies);
    for (const p of persons) {
      addLabel(p.name, () => { const c = people.centreNow(p); return c && add(c, [0, 0, 1.0]); });
    }
  }

  // A dashed path on the ground through the positions P (3 per sample).
  function groundPath(P, colour) {
    const z0 = data.ground.height;
    const pts = [];
    for (let k = 0; k < P.length; k += 3) pts.push(new THREE.Vector3(P[k], P[k + 1], z0 + 0.01));
    const line = new THREE.Line(new THREE.BufferGeometry().setFromPoints(pts),
      new THREE.LineDashedMaterial({ color: colour, dashSize: 0.2, gapSize: 0.12 }));
    line.computeLineDistances();
    pathsGroup.add(line);
  }

  // CG paths (a person's whole-body CG, a bicycle's frame), tyre marks and rest positions.
  function buildPaths() {
    pathsGroup = new THREE.Group();
    for (const p of persons) {
      groundPath(people.cgPath(p), p.colour);
      if (p.bicycle.length) groundPath(people.frame(p).arrays.position, p.shade);
    }
    for (const body of bodies) {
      if (body.kind === 'obstacle' || body.person) continue;
      groundPath(body.arrays.position, body.colour);
      for (const mark of body.tyre_marks || []) {
        const m = new THREE.Line(new THREE.BufferGeometry().setFromPoints(
          mark.map((p) => new THREE.Vector3(p[0], p[1], p[2] + 0.004))),
        new THREE.LineBasicMaterial({ color: 0x222222 }));
        pathsGroup.add(m);
      }
      if (body.rest) {  // a ghost of the vehicle where it came to rest
        const ghost = new THREE.Mesh(body.geometry, new THREE.MeshBasicMaterial({
          color: body.colour, transparent: true, opacity: 0.25, depthWrite: false }));
        ghost.position.set(...body.rest.position);
        ghost.quaternion.copy(toThreeQuaternion(body.rest.orientation));
        const wire = new THREE.LineSegments(new THREE.EdgesGeometry(body.geometry, 30),
          new THREE.LineBasicMaterial({ color: body.colour }));
        ghost.add(wire);
        pathsGroup.add(ghost);
        const p = body.rest.position;
        addLabel(body.name + ' at rest (t = ' + fmt(body.rest.time, 2) + ' s)',
          () => [p[0], p[1], p[2] + 1.0], () => pathsGroup.visible, 'small');
      }
    }
    scene.add(pathsGroup);
  }

  // The overlays of one exchange: region points and box, centroid, normal, arrows.
  async function buildOverlay(imp) {
    const group = new THREE.Group();
    const sizeRef = Math.max(...bodies.map((b) => b.radius));
    const F = imp.contact_frame;  // rows n, t, b: frame coordinates = F x
    const toWorld = (c) => [0, 1, 2].map((i) => F[i] * c[0] + F[3 + i] * c[1] + F[6 + i] * c[2]);
    const lo = imp.region_min, hi = imp.region_max;
    const corners = [];
    for (const a of [lo[0], hi[0]]) for (const b of [lo[1], hi[1]]) for (const c of [lo[2], hi[2]]) {
      corners.push(toWorld([a, b, c]));
    }
    const edges = [[0, 1], [2, 3], [4, 5], [6, 7], [0, 2], [1, 3], [4, 6], [5, 7], [0, 4], [1, 5], [2, 6], [3, 7]];
    const boxPts = [];
    for (const [i, j] of edges) boxPts.push(new THREE.Vector3(...corners[i]), new THREE.Vector3(...corners[j]));
    group.add(new THREE.LineSegments(new THREE.BufferGeometry().setFromPoints(boxPts),
      new THREE.LineBasicMaterial({ color: 0x333333 })));
    const pts = await unpack(imp.region_points);
    const pointsGeometry = new THREE.BufferGeometry();
    pointsGeometry.setAttribute('position', new THREE.BufferAttribute(pts, 3));
    const points = new THREE.Points(pointsGeometry,
      new THREE.PointsMaterial({ color: 0x111111, size: 3, sizeAttenuation: false }));
    points.name = 'points';
    group.add(points);
    const c = imp.centroid;
    const dot3 = new THREE.Mesh(new THREE.SphereGeometry(0.06, 16, 12),
      new THREE.MeshBasicMaterial({ color: 0xe6b800 }));
    dot3.position.set(c[0], c[1], c[2]);
    group.add(dot3);
    const r = Math.max(0.012, sizeRef * 0.006);
    group.add(arrow(c, imp.normal, 0x000000, r * 0.6));  // n: 1 m long
    const colourOf = (name) => (bodies.find((b) => b.name === name) || { colour: '#777' }).colour;
    const [v1, v2] = imp.vehicles;
    const J = imp.impulse, sJ = data.scales.impulse, sV = data.scales.velocity;
    group.add(arrow(c, scale(J, 1 / sJ), colourOf(v2), r));
    group.add(arrow(c, scale(J, -1 / sJ), colourOf(v1), r));
    const shown = () => group.visible && document.getElementById('show-labels').checked;
    addLabel('n', () => add(c, imp.normal), shown, 'small');
    addLabel('exchange ' + imp.number + ': J ' + fmt(norm(J) / 1000, 2) + ' kN s',
      () => add(c, [0, 0, 0.25]), shown, 'small');
    for (const name of imp.vehicles) {
      const body = bodies.find((b) => b.name === name);
      if (!body || body.kind === 'obstacle' || !imp.delta_v[name]) continue;
      const cg = stateAt(body, imp.time).position;
      const dv = imp.delta_v[name];
      group.add(arrow(cg, scale(dv, 1 / sV), body.colour, r * 1.8));
      addLabel('\u0394V ' + name + ' ' + fmt(norm(dv), 2) + ' m/s',
        () => add(add(cg, scale(dv, 1 / sV)), [0, 0, 0.2]), shown, 'small');
    }
    // drawn over the vehicles: the region and the arrows sit inside them
    group.traverse((o) => {
      if (o.material) { o.material.depthTest = false; o.material.transparent = true; }
      o.renderOrder = 10;
    });
    group.visible = false;
    scene.add(group);
    overlays.push({ impact: imp, group: group, points: points });
  }

  const HOLD = 0.1;  // s: an exchange's overlay stays this long after it (or until the next)

  function updateOverlays(t) {
    const all = document.getElementById('show-all').checked;
    const points = document.getElementById('show-points').checked;
    overlays.forEach((o, i) => {
      // shown from its exchange for HOLD s, or until a later exchange
      const ti = o.impact.time;
      const later = overlays.find((p) => p.impact.time > ti);
      const on = t >= ti && t < ti + HOLD && !(later && t >= later.impact.time);
      o.group.visible = all || on;
      o.points.visible = points;
    });
    // while an exchange is shown the vehicles turn translucent, to show what is inside
    const seeThrough = overlays.some((o) => o.group.visible);
    for (const b of bodies) {
      const m = b.object.material;
      m.transparent = seeThrough;
      m.opacity = seeThrough ? 0.45 : 1;
      m.depthWrite = !seeThrough;
    }
  }

  // ---------------------------------------------------------------- camera and drawing

  function render() {
    if (!renderer) return;
    const canvas = renderer.domElement;
    const w = canvas.clientWidth, h = canvas.clientHeight;
    if (canvas.width !== Math.floor(w * devicePixelRatio) || canvas.height !== Math.floor(h * devicePixelRatio)) {
      renderer.setSize(w, h, false);
      camera.aspect = w / h;
      camera.updateProjectionMatrix();
    }
    renderer.render(scene, camera);
    api.frames += 1;
    placeLabels(w, h);
    if (api.firstDrawMs === null) api.firstDrawMs = performance.now();
  }

  function placeLabels(w, h) {
    const show = document.getElementById('show-labels').checked;
    const v = new THREE.Vector3();
    for (const l of labels) {
      const p = show && l.visible() ? l.point() : null;
      if (!p) { l.div.style.display = 'none'; continue; }
      v.set(p[0], p[1], p[2]).project(camera);
      if (v.z > 1 || Math.abs(v.x) > 1.05 || Math.abs(v.y) > 1.05) { l.div.style.display = 'none'; continue; }
      l.div.style.display = '';
      l.div.style.left = ((v.x + 1) / 2 * w).toFixed(1) + 'px';
      l.div.style.top = ((1 - v.y) / 2 * h).toFixed(1) + 'px';
    }
  }

  function centre() { return [0, 1, 2].map((i) => (bounds.lo[i] + bounds.hi[i]) / 2); }
  function extent() { return Math.max(bounds.hi[0] - bounds.lo[0], bounds.hi[1] - bounds.lo[1], 2); }

  // Views: direction from the target to the camera.
  function setView(kind) {
    const c = centre(), d = extent() / (2 * Math.tan((camera.fov * Math.PI) / 360)) * 1.1;
    const dirs = { '3d': [-0.55, -0.75, 0.55], top: [0, -1e-4, 1], side: [0, -1, 0.0] };
    const u = dirs[kind], n = norm(u);
    const dist = kind === 'top' ? d / Math.min(1, camera.aspect) : d;
    controls.target.set(c[0], c[1], kind === 'side' ? (bounds.lo[2] + bounds.hi[2]) / 2 : c[2]);
    camera.position.set(c[0] + (u[0] / n) * dist, c[1] + (u[1] / n) * dist,
      controls.target.z + (u[2] / n) * dist);
    camera.near = dist / 1000; camera.far = dist * 20;
    camera.updateProjectionMatrix();
    controls.update();
    render();
  }

  // The camera to a point p (m), from its present direction, about r m around it in view.
  function focus(p, r) {
    const d = r / Math.tan((camera.fov * Math.PI) / 360);
    const dir = camera.position.clone().sub(controls.target).normalize();
    controls.target.set(p[0], p[1], p[2]);
    camera.position.set(p[0] + dir.x * d, p[1] + dir.y * d, p[2] + dir.z * d);
    camera.near = d / 1000; camera.far = d * 50;
    camera.updateProjectionMatrix();
    controls.update();
    render();
  }

  // The camera to a person (its whole-body CG) or a body (its CG) as drawn now.
  function focusOn(name, r) {
    const p = persons.find((q) => q.name === name);
    const body = bodies.find((b) => b.name === name);
    if (!p && !body) throw new Error('no person or body named ' + name);
    focus(p ? people.centreNow(p) : body.current.position, r || 3);
  }

  // ---------------------------------------------------------------- timeline

  let playing = false, lastFrame = null;
  const T0 = () => samples.t[0], T1 = () => samples.t[samples.t.length - 1];
  const SLIDER_STEPS = 100000;

  function setTime(t, fromSlider) {
    currentTime = Math.min(Math.max(t, T0()), T1());
    for (const body of bodies) {
      const s = stateAt(body, currentTime);
      body.object.position.set(s.position[0], s.position[1], s.position[2]);
      body.object.quaternion.copy(toThreeQuaternion(s.orientation));
      body.current = s;
    }
    updateOverlays(currentTime);
    if (!fromSlider) {
      const span = T1() - T0();
      document.getElementById('slider').value = span > 0 ? Math.round(((currentTime - T0()) / span) * SLIDER_STEPS) : 0;
    }
    let text = 't = ' + fmt(currentTime, 4) + ' s';
    const near = data.impacts.filter((i) => currentTime >= i.time && currentTime < i.time + HOLD).pop();
    if (near) text += '  (exchange ' + near.number + ' at ' + fmt(near.time, 4) + ' s)';
    document.getElementById('time').textContent = text;
    for (const c of cursors) c(currentTime);
    render();
  }

  function tick(now) {
    if (!playing) return;
    const rate = Number(document.getElementById('rate').value);
    const dt = lastFrame === null ? 0 : ((now - lastFrame) / 1000) * rate;
    lastFrame = now;
    let t = currentTime + dt;
    if (t >= T1()) { t = T1(); playing = false; document.getElementById('play').textContent = 'Play'; }
    setTime(t);
    if (playing) requestAnimationFrame(tick);
  }

  function togglePlay() {
    playing = !playing;
    document.getElementById('play').textContent = playing ? 'Pause' : 'Play';
    if (playing) {
      if (currentTime >= T1()) setTime(T0());
      lastFrame = null;
      requestAnimationFrame(tick);
    }
  }

  function buildTimeline() {
    const slider = document.getElementById('slider');
    slider.addEventListener('input', () => {
      setTime(T0() + (Number(slider.value) / SLIDER_STEPS) * (T1() - T0()), true);
    });
    document.getElementById('play').addEventListener('click', togglePlay);
    const markers = document.getElementById('markers');
    const span = T1() - T0() || 1;
    const place = (t, text, cls, title) => {
      const m = el('span', { class: 'marker ' + cls, title: title, text: text });
      m.style.left = (((t - T0()) / span) * 100).toFixed(3) + '%';
      m.addEventListener('click', () => setTime(t));
      markers.appendChild(m);
    };
    for (const c of data.contacts) {
      if (c.kind === 'first_overlap') {
        place(c.time, '\u25B2', 'overlap', 'first overlap ' + c.vehicles.join('-') + ' at ' + fmt(c.time, 6) + ' s');
      }
    }
    for (const i of data.impacts) {
      place(i.time, String(i.number), 'exchange', 'exchange ' + i.number + ' (' + i.vehicles.join('-') +
        ') at ' + fmt(i.time, 6) + ' s');
    }
    document.getElementById('timeline-key').textContent =
      '\u25B2 first overlap, 1 2 ... exchanges (click to jump). Poses from ' + data.samples.kept +
      ' of the run\'s ' + data.samples.total + ' samples, ' +
      (data.interpolation === 'hermite'
        ? 'interpolated between them (Hermite position, slerp orientation) as Result.state does on the ground.'
        : 'carried forward between them by torque-free motion as Result.state does.') +
      ' An exchange\'s overlay shows for ' + HOLD + ' s after it.';
    for (const id of ['show-all', 'show-points', 'show-labels']) {
      document.getElementById(id).addEventListener('change', () => setTime(currentTime));
    }
    document.getElementById('show-paths').addEventListener('change', (e) => {
      pathsGroup.visible = e.target.checked; render();
    });
    document.getElementById('view-3d').addEventListener('click', () => setView('3d'));
    document.getElementById('view-top').addEventListener('click', () => setView('top'));
    document.getElementById('view-side').addEventListener('click', () => setView('side'));
    document.addEventListener('keydown', (e) => {
      if (e.key === ' ' && e.target === document.body) { e.preventDefault(); togglePlay(); }
    });
  }

  function buildLegend() {
    const legend = document.getElementById('legend');
    const swatch = (colour) => { const sw = el('span', { class: 'swatch' }); sw.style.background = colour; return sw; };
    for (const b of bodies) {
      if (b.person) {  // a person once, at its first body
        const p = persons.find((q) => q.name === b.person);
        if (p.members[0] !== b) continue;
        const parts = [swatch(p.colour), p.name + ' (' + p.kind + (p.bicycle.length ? ', ' : ') ')];
        if (p.bicycle.length) parts.push(swatch(p.shade), 'bicycle) ');
        legend.appendChild(el('span', { class: 'person' }, parts));
        continue;
      }
      legend.appendChild(el('span', {}, [swatch(b.colour), b.name + (b.kind === 'obstacle' ? ' (fixed) ' : ' ')]));
    }
    legend.appendChild(el('br'));
    legend.appendChild(document.createTextNode(
      'At an exchange: arrows \u0394V at the CGs 1 m = ' + data.scales.velocity + ' m/s; impulse at the centroid 1 m = ' +
      data.scales.impulse / 1000 + ' kN s; n (black) 1 m; gold: centroid; box and dots: overlap region. Grid ' +
      api.gridStep + ' m.'));
  }

  // ---------------------------------------------------------------- the report panel

  const cursors = [];  // functions moving the plots' time cursors

  let report = null;  // report.js's panel (built last, once the bodies and persons are)

  // ---------------------------------------------------------------- start

  async function main() {
    const t0 = performance.now();
    document.getElementById('three-revision').textContent = THREE.REVISION;
    const canvas = document.getElementById('canvas');
    renderer = new THREE.WebGLRenderer({ canvas: canvas, antialias: true, preserveDrawingBuffer: true });
    renderer.setPixelRatio(window.devicePixelRatio);
    renderer.setClearColor(0xdfe6ea);
    scene = new THREE.Scene();
    camera = new THREE.PerspectiveCamera(35, 1, 0.05, 5000);
    camera.up.set(0, 0, 1);  // the world is z up
    scene.add(new THREE.HemisphereLight(0xffffff, 0x777777, 0.75));
    const sun = new THREE.DirectionalLight(0xffffff, 0.55);
    sun.position.set(-3, -5, 8);
    scene.add(sun);
    await buildBodies();
    buildPersons();
    for (const body of bodies) if (body.kind !== 'obstacle') for (const m of body.tyre_marks || []) for (const p of m) grow(p);
    for (const zone of data.ground.zones) for (const p of zone.polygon) grow([p[0], p[1], data.ground.height]);
    await buildGround();
    buildPaths();
    for (const imp of data.impacts) await buildOverlay(imp);
    controls = new THREE.OrbitControls(camera, canvas);
    controls.addEventListener('change', render);
    buildTimeline();
    buildLegend();
    report = window.crashsimReport({
      data: data, el: el, fmt: fmt, fmtVec: fmtVec, numCell: numCell, kvTable: kvTable,
      norm: norm, qNormalize: qNormalize, qRotate: qRotate, niceStep: niceStep, KMH: KMH, MPH: MPH,
      samples: samples, T0: T0, T1: T1, cursors: cursors, bodies: bodies, persons: persons,
      people: people, setTime: setTime, focusOn: focusOn,
    });
    report.build();
    window.addEventListener('resize', render);
    camera.aspect = canvas.clientWidth / Math.max(1, canvas.clientHeight);
    setView('3d');
    setTime(T0());
    api.setupMs = performance.now() - t0;
    document.getElementById('status').textContent = '';
    document.getElementById('status').style.display = 'none';
    api.ready = true;
  }

  // ---------------------------------------------------------------- the page's API

  api.time = () => currentTime;
  api.setTime = (t) => { setTime(t); return currentTime; };
  api.setView = (kind) => setView(kind);
  api.focus = (name, r) => focusOn(name, r);
  api.focusTarget = () => [controls.target.x, controls.target.y, controls.target.z];
  api.state = (name, t) => {
    const body = bodies.find((b) => b.name === name);
    if (!body) throw new Error('no body named ' + name);
    return stateAt(body, t);
  };
  // The poses drawn now: {name: {position, orientation (w, x, y, z)}}.
  api.poses = () => Object.fromEntries(bodies.map((b) => [b.name, {
    position: b.current.position, orientation: b.current.orientation,
    drawn: [b.object.position.x, b.object.position.y, b.object.position.z],
  }]));

  main().catch((e) => {
    api.error = String(e && e.stack ? e.stack : e);
    const status = document.getElementById('status');
    status.textContent = 'The page could not be drawn: ' + e;
    status.className = 'error';
    console.error(e);
  });
})();
