// A minimal OpenEXR writer: one part, scanline, uncompressed, FLOAT channels, data window = display
// window = the image, row 0 at the top. That is all `shadow-oracle compare --image` needs
// (docs/external.md) and keeps this example free of native modules.
import { Buffer } from 'node:buffer';

function attribute(name, type, data) {
  const size = Buffer.alloc(4);
  size.writeInt32LE(data.length);
  return Buffer.concat([Buffer.from(name + '\0' + type + '\0', 'latin1'), size, data]);
}

function channelList(names) {
  const parts = names.map((n) => {
    const fields = Buffer.alloc(16);
    fields.writeInt32LE(2, 0); // pixel type FLOAT
    fields.writeUInt8(0, 4); // pLinear, then 3 reserved bytes
    fields.writeInt32LE(1, 8); // xSampling
    fields.writeInt32LE(1, 12); // ySampling
    return Buffer.concat([Buffer.from(n + '\0', 'latin1'), fields]);
  });
  return Buffer.concat([...parts, Buffer.from([0])]);
}

/**
 * The bytes of an EXR file. `channels` maps a channel name to a Float32Array of width * height
 * values, row 0 at the top; `strings` are extra string attributes (provenance).
 */
export function encodeExr(width, height, channels, strings = {}) {
  const names = Object.keys(channels).sort(); // OpenEXR keeps the channel list sorted by name
  for (const n of names) {
    if (channels[n].length !== width * height) throw new Error(`channel ${n}: ${channels[n].length} values for ${width} x ${height}`);
  }
  const box = Buffer.alloc(16);
  box.writeInt32LE(0, 0);
  box.writeInt32LE(0, 4);
  box.writeInt32LE(width - 1, 8);
  box.writeInt32LE(height - 1, 12);
  const f32 = (v) => { const b = Buffer.alloc(4); b.writeFloatLE(v); return b; };
  const header = [
    attribute('channels', 'chlist', channelList(names)),
    attribute('compression', 'compression', Buffer.from([0])),
    attribute('dataWindow', 'box2i', box),
    attribute('displayWindow', 'box2i', box),
    attribute('lineOrder', 'lineOrder', Buffer.from([0])),
    attribute('pixelAspectRatio', 'float', f32(1)),
    attribute('screenWindowCenter', 'v2f', Buffer.concat([f32(0), f32(0)])),
    attribute('screenWindowWidth', 'float', f32(1)),
    ...Object.entries(strings).map(([k, v]) => attribute(k, 'string', Buffer.from(String(v), 'utf8'))),
    Buffer.from([0]),
  ];
  const magic = Buffer.alloc(8);
  magic.writeInt32LE(20000630, 0);
  magic.writeInt32LE(2, 4); // version 2, single-part scanline
  const head = Buffer.concat([magic, ...header]);
  const lineBytes = 4 * width * names.length;
  const offsets = Buffer.alloc(8 * height);
  const first = head.length + offsets.length;
  for (let y = 0; y < height; ++y) offsets.writeBigUInt64LE(BigInt(first + y * (8 + lineBytes)), 8 * y);
  const body = Buffer.alloc(height * (8 + lineBytes));
  let at = 0;
  for (let y = 0; y < height; ++y) {
    body.writeInt32LE(y, at);
    body.writeInt32LE(lineBytes, at + 4);
    at += 8;
    for (const n of names) {
      const row = channels[n].subarray(y * width, (y + 1) * width);
      for (let x = 0; x < width; ++x, at += 4) body.writeFloatLE(row[x], at);
    }
  }
  return Buffer.concat([head, offsets, body]);
}
