/** three's split of a scene's materials into its opaque and transparent passes, shared by both compositors. */
import type { Material, Object3D } from 'three';

/** Materials of the scene's renderables, split by three's own rule (transparent → the transparent list). */
export function splitMaterials(scene: Object3D): { opaque: Material[]; transparent: Material[] } {
  const opaque = new Set<Material>();
  const transparent = new Set<Material>();
  scene.traverse((o) => {
    const m = (o as { material?: Material | Material[] }).material;
    if (!m) return;
    for (const mat of Array.isArray(m) ? m : [m]) {
      if (!mat.visible) continue;
      (mat.transparent ? transparent : opaque).add(mat);
    }
  });
  return { opaque: [...opaque], transparent: [...transparent] };
}

export function setVisible(materials: readonly Material[], visible: boolean): void {
  for (const m of materials) m.visible = visible;
}
