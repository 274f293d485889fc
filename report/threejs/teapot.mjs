// three.js's TeapotGeometry as a peer for the speed-vs-error report (scripts/report).
//
// For each segment count N: build new TeapotGeometry(size, N, bottom = lid = body = true,
// fitLid = false, blinn = false) once as a warm-up, then R timed times; write the mesh of the last
// build, mapped back to the coordinates of the BPT (Z up), as DIR/threejs_N.obj, and the counts and
// times as DIR/threejs.json.
//
// Mapping. TeapotGeometry.js (three r187) stores, for a point (x, y, z) of Newell's data,
//   X = s x,   Y = s (1.3 z - h),   Z = -s y,   with h = 3.15 * 1.3 / 2 and s = size / h
// (blinn = false multiplies z by 1.3; then z is centred on h and the model turned to Y up).
// We pass size = h, so s = h / h = 1 exactly, and invert in double precision:
//   x = X / s,   y = -Z / s,   z = (Y / s + h) / 1.3.
// three.js keeps positions in a Float32Array, so the mapped points carry float32 rounding
// (relative 6e-8); the corner check below allows 1e-5 of the BPT's box diagonal.
//
// fitLid is off because it changes the shape: x and y of the lid patches (20-27) times 1.077, which
// no map of the whole mesh undoes. blinn = false stretches z by 1.3 (Blinn's distributed data, the
// BPT's, is squashed by 1.3); that is part of the affine map above and undone by it (blinn = true
// would need h = 3.15 / 2 and no 1.3). So the mesh samples the BPT's exact patches, and the corner
// check proves the inverse: every patch's 4 corner control points must coincide with a mapped
// vertex, or we exit 1 and write nothing.
//
// Time: process.hrtime.bigint() around the constructor alone (Bezier evaluation, normals, uvs,
// index, bounding sphere, as three.js does it); median and minimum of R runs (median of an even R:
// mean of the two middle ones). Mapping, checks and file writing are not timed. Before the first N,
// 100 untimed builds at N = 10 let V8 optimise the constructor: without them the small N run in
// unoptimised code and take 10-30 times longer (N = 2: 5-8 ms cold against 0.2-0.3 ms warm).
//
// Usage: node report/threejs/teapot.mjs --bpt data/teapot.bpt --out DIR
//          [--segments 2,3,4,...] [--repeats R]

import fs from 'node:fs';
import path from 'node:path';
import { parseArgs } from 'node:util';
import { TeapotGeometry } from 'three/addons/geometries/TeapotGeometry.js';

const BLINN_SCALE = 1.3;              // TeapotGeometry.js: blinnScale
const H = (3.15 * BLINN_SCALE) / 2;   // TeapotGeometry.js: maxHeight2 with blinn = false
const SIZE = H;                       // so that trueSize = size / maxHeight2 = 1
const S = SIZE / H;

function fail(status, message) {
  process.stderr.write(`teapot.mjs: ${message}\n`);
  process.exit(status);
}

function positive_int(text, what, min) {
  if (!/^\d+$/.test(text) || Number(text) < min) fail(2, `${what}: '${text}' is not an integer >= ${min}`);
  return Number(text);
}

function parse_options() {
  let values;
  try {
    ({ values } = parseArgs({ options: {
      bpt: { type: 'string' }, out: { type: 'string' },
      segments: { type: 'string', default: '2,3,4,6,8,10,12,16,24,32,48,64,96,128' },
      repeats: { type: 'string', default: '5' } } }));
  } catch (error) {
    fail(2, `${error.message} (usage: --bpt FILE --out DIR [--segments N,N,...] [--repeats R])`);
  }
  if (values.bpt === undefined || values.out === undefined) fail(2, 'usage: --bpt FILE --out DIR [--segments N,N,...] [--repeats R]');
  // Integers >= 2 only: three.js would clamp max(2, floor(N)) silently.
  const segments = values.segments.split(',').map((t) => positive_int(t.trim(), '--segments', 2));
  return { bpt: values.bpt, out: values.out, segments, repeats: positive_int(values.repeats, '--repeats', 1) };
}

// BPT: the patch count; per patch "n m", then (n+1)(m+1) lines "x y z", first index fastest.
// Returns per patch its 4 corner control points.
function read_bpt_corners(file) {
  let text;
  try { text = fs.readFileSync(file, 'utf8'); } catch (error) { fail(1, `${file}: ${error.message}`); }
  const lines = text.split('\n');
  let at = 0;
  const numbers = (count) => {
    while (at < lines.length && lines[at].trim() === '') at++;
    const fields = at < lines.length ? lines[at].trim().split(/\s+/).map(Number) : [];
    if (fields.length !== count || !fields.every(Number.isFinite)) fail(1, `${file}:${at + 1}: expected ${count} numbers`);
    at++;
    return fields;
  };
  const [patch_count] = numbers(1);
  if (!Number.isInteger(patch_count) || patch_count < 1) fail(1, `${file}:1: bad patch count`);
  const corners = [];
  for (let p = 0; p < patch_count; p++) {
    const [n, m] = numbers(2);
    if (!Number.isInteger(n) || !Number.isInteger(m) || n < 1 || m < 1) fail(1, `${file}:${at}: bad degrees`);
    const P = Array.from({ length: (n + 1) * (m + 1) }, () => numbers(3));
    corners.push([P[0], P[n], P[(n + 1) * m], P[(n + 1) * (m + 1) - 1]]);
  }
  return corners;
}

// Float32 position of three.js (Y up) -> double in the BPT's frame (Z up), the inverse above.
function map_back(positions) {
  const out = new Float64Array(positions.length);
  for (let k = 0; k < positions.length; k += 3) {
    out[k] = positions[k] / S;
    out[k + 1] = -positions[k + 2] / S;
    out[k + 2] = (positions[k + 1] / S + H) / BLINN_SCALE;
  }
  return out;
}

// Largest distance from a patch corner to its nearest mesh vertex, and where it is.
function corner_deviation(corners, points) {
  let worst = { distance: 0, patch: -1, corner: -1 };
  corners.forEach((patch, p) => patch.forEach(([x, y, z], c) => {
    let best = Infinity;
    for (let k = 0; k < points.length; k += 3) {
      const d = (points[k] - x) ** 2 + (points[k + 1] - y) ** 2 + (points[k + 2] - z) ** 2;
      if (d < best) best = d;
    }
    if (Math.sqrt(best) > worst.distance) worst = { distance: Math.sqrt(best), patch: p, corner: c };
  }));
  return worst;
}

// Triangles with two equal indices or exactly zero area (cross product zero in the mapped doubles).
function degenerate_count(points, index) {
  let count = 0;
  for (let t = 0; t < index.length; t += 3) {
    const [a, b, c] = [index[t] * 3, index[t + 1] * 3, index[t + 2] * 3];
    const u = [points[b] - points[a], points[b + 1] - points[a + 1], points[b + 2] - points[a + 2]];
    const v = [points[c] - points[a], points[c + 1] - points[a + 1], points[c + 2] - points[a + 2]];
    const cross_zero = u[1] * v[2] === u[2] * v[1] && u[2] * v[0] === u[0] * v[2] && u[0] * v[1] === u[1] * v[0];
    if (a === b || b === c || a === c || cross_zero) count++;
  }
  return count;
}

function write_whole(file, text) {
  fs.writeFileSync(`${file}.tmp`, text);
  fs.renameSync(`${file}.tmp`, file);
}

function obj_text(points, index) {
  const lines = [];
  for (let k = 0; k < points.length; k += 3) lines.push(`v ${points[k]} ${points[k + 1]} ${points[k + 2]}`);
  for (let t = 0; t < index.length; t += 3) lines.push(`f ${index[t] + 1} ${index[t + 1] + 1} ${index[t + 2] + 1}`);
  return lines.join('\n') + '\n';
}

const build = (N) => new TeapotGeometry(SIZE, N, true, true, true, false, false);

const options = parse_options();
const corners = read_bpt_corners(options.bpt);
const box_lo = [Infinity, Infinity, Infinity], box_hi = [-Infinity, -Infinity, -Infinity];
for (const point of corners.flat()) point.forEach((x, i) => { box_lo[i] = Math.min(box_lo[i], x); box_hi[i] = Math.max(box_hi[i], x); });
const tolerance = 1e-5 * Math.hypot(...box_hi.map((x, i) => x - box_lo[i]));

// Build, time and check every N before writing anything.
const results = [];
let max_deviation = 0;
for (let i = 0; i < 100; i++) build(10);
for (const N of options.segments) {
  build(N);
  const seconds = [];
  let geometry;
  for (let r = 0; r < options.repeats; r++) {
    const start = process.hrtime.bigint();
    geometry = build(N);
    seconds.push(Number(process.hrtime.bigint() - start) * 1e-9);
  }
  seconds.sort((a, b) => a - b);
  const mid = seconds.length >> 1;
  const median = seconds.length % 2 ? seconds[mid] : (seconds[mid - 1] + seconds[mid]) / 2;
  const points = map_back(geometry.getAttribute('position').array);
  const index = geometry.getIndex().array;
  const worst = corner_deviation(corners, points);
  if (worst.distance > tolerance) {
    fs.rmSync(path.join(options.out, 'threejs.json'), { force: true });  // no stale result either
    fail(1, `N=${N}: patch ${worst.patch} corner ${worst.corner} is ${worst.distance} from the nearest ` +
      `three.js vertex (tolerance ${tolerance}); the mapping is wrong, nothing written`);
  }
  max_deviation = Math.max(max_deviation, worst.distance);
  results.push({ N, points, index, run: { segments: N, triangles: index.length / 3, vertices: points.length / 3,
    degenerate_triangles: degenerate_count(points, index), seconds_median: median, seconds_min: seconds[0],
    repeats: options.repeats } });
}

try {
  fs.mkdirSync(options.out, { recursive: true });
  for (const { N, points, index } of results) write_whole(path.join(options.out, `threejs_${N}.obj`), obj_text(points, index));
  const version = JSON.parse(fs.readFileSync(new URL('./node_modules/three/package.json', import.meta.url), 'utf8')).version;
  write_whole(path.join(options.out, 'threejs.json'), JSON.stringify({
    three_version: version, size: SIZE,
    mapping: `three (X,Y,Z) = s (x, 1.3 z - h, -y), h = 3.15*1.3/2, s = size/h = ${S}; inverse x = X/s, y = -Z/s, z = (Y/s + h)/1.3`,
    max_corner_deviation: max_deviation, runs: results.map((r) => r.run) }, null, 1) + '\n');
} catch (error) {
  fail(1, `${options.out}: ${error.message}`);
}
for (const { run } of results) {
  console.log(`N=${run.segments}: ${run.triangles} triangles, ${run.vertices} vertices, ${run.degenerate_triangles} degenerate, ` +
    `median ${run.seconds_median.toExponential(3)} s, min ${run.seconds_min.toExponential(3)} s`);
}
console.log(`max corner deviation ${max_deviation} (tolerance ${tolerance})`);
