// The gallery's datasets: bundled ones (in the repository) and procedural ones.
// Transfer functions are tuned per dataset; cameras follow each scan's orientation.
export const DATASETS = [
  {
    id: 'head',
    title: 'MRI head (VolPack, 128×128×84)',
    raw: '/data/mri_head_volpack_brainsmall_128x128x84_uint8.raw',
    dims: [128, 128, 84], type: 'uint8', spacing: [1, 1, 1],
    // y runs from the top of the head down, x from the face backwards: look at the face, y down.
    camera: { position: [-1.6, -0.35, 0.55], target: [0, 0, 0], up: [0, -1, 0], fovy: 0.75 },
    transferFunction: { dimensions: '1d', points: [
      { value: 0.0, color: [0, 0, 0], opacity: 0 },
      { value: 0.15, color: [0.5, 0.2, 0.1], opacity: 0 },
      { value: 0.3, color: [0.9, 0.5, 0.35], opacity: 0.02 },
      { value: 0.5, color: [1.0, 0.85, 0.7], opacity: 0.08 },
      { value: 0.7, color: [2.0, 1.9, 1.8], opacity: 0.5 },
      { value: 1.0, color: [3, 3, 3], opacity: 1 },
    ] },
    densityScale: 80,
  },
  {
    id: 'blob', title: 'Procedural Gaussian blob (64³)', procedural: 'blob', size: 64,
    camera: { position: [1.2, 0.8, 1.4], target: [0, 0, 0], up: [0, 1, 0], fovy: 0.7 },
    transferFunction: { dimensions: '1d', points: [
      { value: 0.05, color: [0.1, 0.3, 1], opacity: 0 }, { value: 0.5, color: [1, 0.6, 0.2], opacity: 0.5 }, { value: 1, color: [4, 3, 2], opacity: 1 },
    ] },
  },
];
