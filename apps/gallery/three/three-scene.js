// The gallery's three.js page: the bundled MRI head as a VptVolume (@vpt/three) in a
// three.js scene with an opaque cylinder through it (a probe), a floor grid and a
// transparent marker, orbited with OrbitControls; the viewer's <vpt-tf-editor> (from
// @vpt/viewer/tf-editor) edits the volume's transfer function. Bundled by build.mjs (Rollup) into
// dist/assets/three-scene.js.
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { VptVolume, VptCompositor } from '@vpt/three';
import { createVolume } from '@vpt/core';
import { EamRenderer } from '@vpt/renderer-eam';
import { McrtRenderer } from '@vpt/renderer-mcrt';
// Defines <vpt-tf-editor> alone (not the viewer element); valueHistogram for its backdrop.
import { valueHistogram } from '@vpt/viewer/tf-editor';

const HEAD = 'data/mri_head_volpack_brainsmall_128x128x84_uint8';

async function loadHead() {
  const meta = await (await fetch(`${HEAD}.json`)).json();
  const raw = new Uint8Array(await (await fetch(`${HEAD}.raw`)).arrayBuffer());
  const volume = createVolume(meta.dims, 'uint8', raw, meta.spacing);
  volume.valueRange = meta.value_range;
  return volume;
}

async function presetOf(name) {
  // The headless CLI's scene files double as the head's presets (TF, density, lights).
  return (await fetch(`scenes/head-${name}.json`)).json();
}

function vptScene(volume, preset) {
  return {
    volume,
    transferFunction: preset.transferFunction,
    lights: preset.lights ?? [{ type: 'directional', direction: [0.4, 0.8, 0.45], irradiance: [3, 3, 3] }],
    environment: preset.environment ?? { type: 'constant', radiance: [0.05, 0.05, 0.06] },
    densityScale: preset.densityScale ?? 40,
    seed: 1,
  };
}

async function main() {
  const canvas = document.getElementById('three-view');
  const status = document.getElementById('status');
  const renderer = new THREE.WebGLRenderer({ canvas, antialias: false });
  renderer.setPixelRatio(Math.min(window.devicePixelRatio, 1.5));
  renderer.toneMapping = THREE.ACESFilmicToneMapping;
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0x20242c);
  const camera = new THREE.PerspectiveCamera(40, 1, 0.05, 20);
  camera.position.set(0.2, 0.25, 1.9);
  const controls = new OrbitControls(camera, canvas);

  scene.add(new THREE.HemisphereLight(0xffffff, 0x334455, 1.5));
  const sun = new THREE.DirectionalLight(0xffffff, 2);
  sun.position.set(1, 2, 1.5);
  scene.add(sun);
  const grid = new THREE.GridHelper(2, 20, 0x667788, 0x3a4250);
  grid.position.y = -0.5;
  scene.add(grid);
  // The probe: an opaque cylinder through the head.
  const probe = new THREE.Mesh(
    new THREE.CylinderGeometry(0.025, 0.025, 1.4, 24),
    new THREE.MeshStandardMaterial({ color: 0x4fa3ff, metalness: 0.3, roughness: 0.4 }),
  );
  probe.rotation.z = Math.PI / 3;
  probe.rotation.x = 0.3;
  scene.add(probe);
  // A transparent marker at the probe's tip, drawn after the volume.
  const tip = new THREE.Mesh(
    new THREE.SphereGeometry(0.05, 24, 12),
    new THREE.MeshBasicMaterial({ color: 0xffcc33, transparent: true, opacity: 0.6 }),
  );
  tip.position.set(-0.6 * Math.sin(Math.PI / 3), 0.6 * Math.cos(Math.PI / 3) * Math.cos(0.3), 0.6 * Math.sin(0.3));
  scene.add(tip);

  status.value = 'loading the head…';
  const volume = await loadHead();
  const presets = { eam: await presetOf('eam'), mcrt: await presetOf('mcrt') };
  const makeVolume = (name) => {
    const v = new VptVolume({
      renderer: name === 'mcrt' ? new McrtRenderer(presets.mcrt.rendererParams ?? {}) : new EamRenderer(),
      scene: vptScene(volume, presets[name]),
      iterationsPerFrame: 1,
      maxSamples: 512,
    });
    // The head's axes run posterior, inferior, right (its sidecar's "PIR"): turn it upright, face to +z.
    v.quaternion.setFromRotationMatrix(
      new THREE.Matrix4().makeBasis(
        new THREE.Vector3(0, 0, -1),
        new THREE.Vector3(0, -1, 0),
        new THREE.Vector3(-1, 0, 0),
      ),
    );
    return v;
  };
  let head = makeVolume('eam');
  scene.add(head);
  // The viewer's TF editor on the head's histogram: each edit replaces the volume's scene
  // (setScene), which restarts its accumulation.
  const editor = document.getElementById('tf-editor');
  editor.histogram = valueHistogram(volume);
  editor.value = head.scene.transferFunction;
  const applyTf = (e) => {
    const tf = e.detail.transferFunction;
    if (tf) head.setScene({ ...head.scene, transferFunction: tf });
  };
  editor.addEventListener('input', applyTf);
  editor.addEventListener('change', applyTf);
  const compositor = new VptCompositor(renderer);

  document.getElementById('renderer').addEventListener('change', (e) => {
    scene.remove(head);
    head.dispose();
    head = makeVolume(e.target.value);
    editor.value = head.scene.transferFunction;
    scene.add(head);
  });
  document.getElementById('probe').addEventListener('change', (e) => {
    probe.visible = tip.visible = e.target.checked;
  });

  const resize = () => {
    const w = canvas.clientWidth;
    const h = canvas.clientHeight;
    renderer.setSize(w, h, false);
    camera.aspect = w / h;
    camera.updateProjectionMatrix();
  };
  new ResizeObserver(resize).observe(canvas);
  resize();
  window.threePage = {
    renderer,
    scene,
    camera,
    compositor,
    editor,
    get head() {
      return head;
    },
  };
  window.__threeReady = true;
  renderer.setAnimationLoop(() => {
    controls.update();
    compositor.render(scene, camera);
    status.value = `${head.sampleCount} samples per pixel`;
  });
}

main().catch((e) => {
  document.getElementById('status').value = `error: ${e.message}`;
  console.error(e);
});
