/**
 * The uniform layout is declared once here, as an ordered list of typed fields.
 * From it we derive the std140 block (GLSL ES 3.0), the WGSL struct (uniform
 * address space) and a packer that writes values at the derived offsets.
 *
 * Rules (GLSL ES 3.0 spec §2.12.6.4 "std140"; WGSL spec §13.4 "Memory Layout"):
 *   type    align  size
 *   f32/i32/u32  4  4
 *   vec2    8      8
 *   vec3    16     12   (the next scalar may sit in the 4 trailing bytes)
 *   vec4    16     16
 *   mat4    16     64   (4 columns of vec4)
 *   arrays of N (std140 and WGSL uniform): element stride rounded up to 16.
 * Block size is rounded up to 16 (both).
 */
export type UniformType = 'f32' | 'i32' | 'u32' | 'vec2' | 'vec3' | 'vec4' | 'ivec4' | 'uvec4' | 'mat4';

export interface UniformField {
  name: string;
  type: UniformType;
  /** Array length; omitted for a single value. */
  count?: number;
}

export interface FieldPlacement extends UniformField {
  offset: number; // bytes
  stride: number; // bytes between array elements (or the size, for a single value)
}

const ALIGN: Record<UniformType, number> = {
  f32: 4,
  i32: 4,
  u32: 4,
  vec2: 8,
  vec3: 16,
  vec4: 16,
  ivec4: 16,
  uvec4: 16,
  mat4: 16,
};
const SIZE: Record<UniformType, number> = {
  f32: 4,
  i32: 4,
  u32: 4,
  vec2: 8,
  vec3: 12,
  vec4: 16,
  ivec4: 16,
  uvec4: 16,
  mat4: 64,
};
const GLSL_TYPE: Record<UniformType, string> = {
  f32: 'float',
  i32: 'int',
  u32: 'uint',
  vec2: 'vec2',
  vec3: 'vec3',
  vec4: 'vec4',
  ivec4: 'ivec4',
  uvec4: 'uvec4',
  mat4: 'mat4',
};
const WGSL_TYPE: Record<UniformType, string> = {
  f32: 'f32',
  i32: 'i32',
  u32: 'u32',
  vec2: 'vec2f',
  vec3: 'vec3f',
  vec4: 'vec4f',
  ivec4: 'vec4i',
  uvec4: 'vec4u',
  mat4: 'mat4x4f',
};

const roundUp = (n: number, a: number) => Math.ceil(n / a) * a;

export type UniformValue = number | ArrayLike<number>;
export type UniformValues = Record<string, UniformValue>;

export class UniformLayout {
  readonly fields: readonly FieldPlacement[];
  /** Total byte size, a multiple of 16. */
  readonly byteSize: number;
  private readonly byName = new Map<string, FieldPlacement>();

  constructor(
    readonly structName: string,
    fields: readonly UniformField[],
  ) {
    let offset = 0;
    const placed: FieldPlacement[] = [];
    for (const f of fields) {
      if (!/^[A-Za-z_][A-Za-z0-9_]*$/.test(f.name)) throw new Error(`bad uniform name "${f.name}"`);
      if (this.byName.has(f.name)) throw new Error(`duplicate uniform "${f.name}"`);
      if (f.count !== undefined && SIZE[f.type] % 16 !== 0) {
        // std140 pads float[N] to stride 16 while WGSL forbids array<f32> in uniforms:
        // arrays are limited to 16-byte element types so both languages index them alike.
        throw new Error(`uniform array "${f.name}" must use vec4, ivec4, uvec4 or mat4 elements`);
      }
      const isArray = f.count !== undefined;
      const align = isArray ? roundUp(ALIGN[f.type], 16) : ALIGN[f.type];
      const stride = isArray ? roundUp(SIZE[f.type], 16) : SIZE[f.type];
      offset = roundUp(offset, align);
      const p: FieldPlacement = { ...f, offset, stride };
      placed.push(p);
      this.byName.set(f.name, p);
      offset += isArray ? stride * f.count! : SIZE[f.type];
    }
    this.fields = placed;
    this.byteSize = Math.max(16, roundUp(offset, 16));
  }

  field(name: string): FieldPlacement {
    const f = this.byName.get(name);
    if (!f) throw new Error(`uniform "${name}" is not in ${this.structName}`);
    return f;
  }

  /** `layout(std140) uniform <Struct>Block { … } u;` — fields read as u.name in GLSL. */
  glslBlock(instance = 'u'): string {
    const lines = this.fields.map(
      (f) => `  ${GLSL_TYPE[f.type]} ${f.name}${f.count !== undefined ? `[${f.count}]` : ''};`,
    );
    return `layout(std140) uniform ${this.structName}Block {\n${lines.join('\n')}\n} ${instance};\n`;
  }

  /** `struct <Struct> { … }` — bound as var<uniform> u, so fields read as u.name in WGSL too. */
  wgslStruct(): string {
    const lines = this.fields.map((f) => {
      const t = WGSL_TYPE[f.type];
      return `  ${f.name}: ${f.count !== undefined ? `array<${arrayElementType(f.type)}, ${f.count}>` : t},`;
    });
    return `struct ${this.structName} {\n${lines.join('\n')}\n};\n`;
  }

  /** Pack values into a new buffer (or `into`). Missing fields are zero. */
  pack(values: UniformValues, into?: ArrayBuffer): ArrayBuffer {
    const buf = into ?? new ArrayBuffer(this.byteSize);
    const f32 = new Float32Array(buf);
    const i32 = new Int32Array(buf);
    const u32 = new Uint32Array(buf);
    if (into) f32.fill(0);
    for (const [name, value] of Object.entries(values)) {
      const f = this.field(name);
      const count = f.count ?? 1;
      const comps = componentsOf(f.type);
      const view = f.type === 'i32' || f.type === 'ivec4' ? i32 : f.type === 'u32' || f.type === 'uvec4' ? u32 : f32;
      const flat: ArrayLike<number> = typeof value === 'number' ? [value] : value;
      if (flat.length !== comps * count) {
        throw new Error(
          `uniform "${name}" (${f.type}${f.count !== undefined ? `[${f.count}]` : ''}) takes ${comps * count} numbers, got ${flat.length}`,
        );
      }
      for (let e = 0; e < count; e++) {
        const base = (f.offset + e * f.stride) / 4;
        for (let c = 0; c < comps; c++) view[base + c] = flat[e * comps + c];
      }
    }
    return buf;
  }
}

function componentsOf(t: UniformType): number {
  return t === 'mat4'
    ? 16
    : t === 'vec4' || t === 'ivec4' || t === 'uvec4'
      ? 4
      : t === 'vec3'
        ? 3
        : t === 'vec2'
          ? 2
          : 1;
}

function arrayElementType(t: UniformType): string {
  return WGSL_TYPE[t];
}
