// Writes gltf_transform.glb with the npm package @gltf-transform (an independent glTF writer:
// interleaved vertex buffers with byteStride, its own .glb layout) for tests/scene/test_gltf.c.
// The published 4.5.1 has no KHR_materials_volume_scatter yet, so this asset covers volume, ior,
// diffuse transmission (a volume with diffuse transmission and no scattering extension imports as
// the nearest subsurface medium, docs/gltf.md), lights, a camera and a TRS hierarchy. Regenerate:
//   (cd /tmp/gt && npm install @gltf-transform/core@4.5.1 @gltf-transform/extensions@4.5.1)
//   NODE_PATH=/tmp/gt/node_modules node make_gltf_transform.cjs [OUT_DIR]
const { Document, NodeIO, VertexLayout } = require('@gltf-transform/core');
const ext = require('@gltf-transform/extensions');
const path = require('path');

const out = process.argv[2] || __dirname;
const doc = new Document();
const buffer = doc.createBuffer();

// A box 1 x 2 x 1 around the origin: 8 corners, 12 triangles counter-clockwise seen from outside.
const corners = [];
for (let i = 0; i < 8; i++) corners.push((i & 1 ? 0.5 : -0.5), (i & 2 ? 1 : -1), (i & 4 ? 0.5 : -0.5));
const quads = [[0, 4, 6, 2], [1, 3, 7, 5], [0, 1, 5, 4], [2, 6, 7, 3], [0, 2, 3, 1], [4, 5, 7, 6]];
const indices = [];
for (const [a, b, c, d] of quads) indices.push(a, b, c, a, c, d);
const position = doc.createAccessor().setType('VEC3').setArray(new Float32Array(corners)).setBuffer(buffer);
const index = doc.createAccessor().setType('SCALAR').setArray(new Uint32Array(indices)).setBuffer(buffer);

const volumeExt = doc.createExtension(ext.KHRMaterialsVolume).setRequired(true);
const iorExt = doc.createExtension(ext.KHRMaterialsIOR);
const transmissionExt = doc.createExtension(ext.KHRMaterialsDiffuseTransmission);
const lightsExt = doc.createExtension(ext.KHRLightsPunctual);

const glass = doc.createMaterial('volume').setBaseColorFactor([0.3, 0.5, 0.7, 1])
    .setExtension('KHR_materials_volume', volumeExt.createVolume().setThicknessFactor(1)
        .setAttenuationDistance(0.5).setAttenuationColor([0.6, 0.4, 0.2]))
    .setExtension('KHR_materials_ior', iorExt.createIOR().setIOR(1.3))
    .setExtension('KHR_materials_diffuse_transmission', transmissionExt.createDiffuseTransmission()
        .setDiffuseTransmissionFactor(1));
const prim = doc.createPrimitive().setAttribute('POSITION', position).setIndices(index).setMaterial(glass);
const mesh = doc.createMesh('box').addPrimitive(prim);

const s = Math.sin(Math.PI / 8); // the quaternion of 45 degrees about z: (0, 0, sin 22.5, cos 22.5)
const child = doc.createNode('child').setMesh(mesh).setTranslation([0, 1, 0]).setRotation([0, 0, s, Math.cos(Math.PI / 8)]);
const root = doc.createNode('root').setScale([2, 2, 2]).addChild(child);
const camera = doc.createCamera('camera').setType('perspective').setYFov(0.7).setAspectRatio(4 / 3)
    .setZNear(0.1).setZFar(100);
const cameraNode = doc.createNode('camera').setCamera(camera).setTranslation([0, 0, 10]);
const light = lightsExt.createLight('point').setType('point').setIntensity(12).setColor([1, 0.8, 0.6]);
const lightNode = doc.createNode('light').setTranslation([3, 4, 5]).setExtension('KHR_lights_punctual', light);
doc.createScene('scene').addChild(root).addChild(cameraNode).addChild(lightNode);

const io = new NodeIO().registerExtensions([ext.KHRMaterialsVolume, ext.KHRMaterialsIOR,
    ext.KHRMaterialsDiffuseTransmission, ext.KHRLightsPunctual]).setVertexLayout(VertexLayout.INTERLEAVED);
io.write(path.join(out, 'gltf_transform.glb'), doc).then(() => console.log('wrote gltf_transform.glb'));
