// Writes a glTF scene as another tool makes it (glTF-Transform's NodeIO, npm
// @gltf-transform/core), for meshsal's tests of files it did not write:
//   node web/make_gltf_scene.mjs OUT_DIR
// OUT_DIR/scene.glb (everything embedded) and OUT_DIR/scene.gltf with scene.bin and
// texture.png beside it: one mesh of a wavy 16 x 16 grid whose two halves are two primitives
// sharing their vertex accessors (POSITION, NORMAL, TEXCOORD_0), one half under a material
// with a base-colour texture, the other under a plain one; the mesh under a node rotated a
// quarter turn about y, itself under a node translated and scaled.
import { Document, NodeIO } from '@gltf-transform/core';
import { deflateSync } from 'node:zlib';
import path from 'node:path';

// A PNG of w x h RGB pixels (a checker), written here: no image library needed.
function png(w, h) {
  const crcTable = new Uint32Array(256).map((_, n) => {
    let c = n;
    for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
    return c >>> 0;
  });
  const crc = (bytes) => {
    let c = 0xffffffff;
    for (const b of bytes) c = crcTable[(c ^ b) & 0xff] ^ (c >>> 8);
    return (c ^ 0xffffffff) >>> 0;
  };
  const chunk = (type, data) => {
    const out = Buffer.alloc(12 + data.length);
    out.writeUInt32BE(data.length, 0);
    out.write(type, 4, 'ascii');
    data.copy(out, 8);
    out.writeUInt32BE(crc(out.subarray(4, 8 + data.length)), 8 + data.length);
    return out;
  };
  const header = Buffer.alloc(13);
  header.writeUInt32BE(w, 0);
  header.writeUInt32BE(h, 4);
  header[8] = 8;  // bit depth
  header[9] = 2;  // RGB
  const rows = Buffer.alloc(h * (1 + 3 * w));
  for (let y = 0; y < h; y++)
    for (let x = 0; x < w; x++) {
      const on = (x >> 2) % 2 === (y >> 2) % 2;
      rows.set(on ? [200, 60, 40] : [240, 230, 200], y * (1 + 3 * w) + 1 + 3 * x);
    }
  return Buffer.concat([Buffer.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]), chunk('IHDR', header),
                        chunk('IDAT', deflateSync(rows)), chunk('IEND', Buffer.alloc(0))]);
}

const out = process.argv[2];
const doc = new Document();
const buffer = doc.createBuffer('scene').setURI('scene.bin');
const n = 16;
const positions = [], normals = [], uvs = [], left = [], right = [];
for (let j = 0; j <= n; j++)
  for (let i = 0; i <= n; i++) {
    const x = i / n - 0.5, y = j / n - 0.5, z = 0.08 * Math.sin(6 * x) * Math.cos(5 * y);
    positions.push(x, y, z);
    normals.push(0, 0, 1);
    uvs.push(i / n, 1 - j / n);
  }
for (let j = 0; j < n; j++)
  for (let i = 0; i < n; i++) {
    const a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
    (i < n / 2 ? left : right).push(a, b, d, a, d, c);
  }
const accessor = (type, array) => doc.createAccessor().setType(type).setArray(array).setBuffer(buffer);
const position = accessor('VEC3', new Float32Array(positions));
const normal = accessor('VEC3', new Float32Array(normals));
const uv = accessor('VEC2', new Float32Array(uvs));
const texture = doc.createTexture('checker').setImage(new Uint8Array(png(16, 16))).setMimeType('image/png').setURI('texture.png');
const painted = doc.createMaterial('painted').setBaseColorTexture(texture).setMetallicFactor(0.1);
const plain = doc.createMaterial('plain').setBaseColorFactor([0.2, 0.5, 0.8, 1]).setRoughnessFactor(0.7);
const mesh = doc.createMesh('grid');
for (const [indices, material] of [[left, painted], [right, plain]])
  mesh.addPrimitive(doc.createPrimitive().setAttribute('POSITION', position).setAttribute('NORMAL', normal)
    .setAttribute('TEXCOORD_0', uv).setIndices(accessor('SCALAR', new Uint32Array(indices))).setMaterial(material));
const turned = doc.createNode('turned').setMesh(mesh).setRotation([0, Math.SQRT1_2, 0, Math.SQRT1_2]);
const placed = doc.createNode('placed').setTranslation([10, 0, -5]).setScale([2, 2, 2]).addChild(turned);
doc.createScene('scene').addChild(placed);
doc.getRoot().getAsset().generator = 'glTF-Transform (meshsal tests)';

const io = new NodeIO();
await io.write(path.join(out, 'scene.gltf'), doc);
await io.write(path.join(out, 'scene.glb'), doc);
