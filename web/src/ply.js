// Reads the vertices' x, y, z of a binary little-endian PLY (what rangefitd spools: float64, mm)
// into a Float32Array, keeping at most maxPoints (evenly strided) so the view stays responsive.
const SIZES = { char: 1, uchar: 1, int8: 1, uint8: 1, short: 2, ushort: 2, int16: 2, uint16: 2,
  int: 4, uint: 4, int32: 4, uint32: 4, float: 4, float32: 4, double: 8, float64: 8 };

function reader(view, type) {
  switch (type) {
    case 'char': case 'int8': return (o) => view.getInt8(o);
    case 'uchar': case 'uint8': return (o) => view.getUint8(o);
    case 'short': case 'int16': return (o) => view.getInt16(o, true);
    case 'ushort': case 'uint16': return (o) => view.getUint16(o, true);
    case 'int': case 'int32': return (o) => view.getInt32(o, true);
    case 'uint': case 'uint32': return (o) => view.getUint32(o, true);
    case 'float': case 'float32': return (o) => view.getFloat32(o, true);
    default: return (o) => view.getFloat64(o, true);
  }
}

export function parsePly(buffer, maxPoints = 250000) {
  const bytes = new Uint8Array(buffer);
  const headerEnd = new TextDecoder().decode(bytes.subarray(0, Math.min(bytes.length, 4096)))
    .indexOf('end_header\n');
  if (headerEnd < 0) throw new Error('not a PLY file');
  const header = new TextDecoder().decode(bytes.subarray(0, headerEnd)).split('\n');
  if (!header.some((l) => l.startsWith('format binary_little_endian'))) {
    throw new Error('only binary little-endian PLY is shown');
  }
  let count = 0;
  let inVertex = false;
  let stride = 0;
  const offsets = {};
  const types = {};
  for (const line of header) {
    const w = line.trim().split(/\s+/);
    if (w[0] === 'element') {
      inVertex = w[1] === 'vertex';
      if (inVertex) count = parseInt(w[2], 10);
    } else if (w[0] === 'property' && inVertex) {
      if (w[1] === 'list') throw new Error('list properties in vertices are not supported');
      offsets[w[2]] = stride;
      types[w[2]] = w[1];
      stride += SIZES[w[1]] || 8;
    }
  }
  if (!('x' in offsets && 'y' in offsets && 'z' in offsets)) throw new Error('no x, y, z');
  const view = new DataView(buffer, headerEnd + 'end_header\n'.length);
  if (view.byteLength < count * stride) throw new Error('PLY shorter than its header says');
  const step = Math.max(1, Math.ceil(count / maxPoints));
  const n = Math.floor((count + step - 1) / step);
  const positions = new Float32Array(n * 3);
  const rx = reader(view, types.x), ry = reader(view, types.y), rz = reader(view, types.z);
  let k = 0;
  for (let i = 0; i < count; i += step) {
    const o = i * stride;
    positions[k++] = rx(o + offsets.x);
    positions[k++] = ry(o + offsets.y);
    positions[k++] = rz(o + offsets.z);
  }
  return { count, shown: n, positions };
}
