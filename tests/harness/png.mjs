// The PNG reading and writing the harness needs for its difference images: 8-bit,
// non-interlaced gray, gray + alpha, RGB and RGBA (what lodopt and Chromium write), through
// node's zlib. Anything else is refused with the reason.
import zlib from 'node:zlib';

const kSignature = Buffer.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]);
const kChannels = { 0: 1, 2: 3, 4: 2, 6: 4 };

// {width, height, rgb: Uint8Array(width * height * 3)} of the PNG in `bytes`.
export function decodePng(bytes) {
    if (!bytes.subarray(0, 8).equals(kSignature)) throw new Error('not a PNG');
    let offset = 8;
    let header = null;
    const data = [];
    while (offset + 8 <= bytes.length) {
        const length = bytes.readUInt32BE(offset);
        const type = bytes.toString('latin1', offset + 4, offset + 8);
        const body = bytes.subarray(offset + 8, offset + 8 + length);
        if (type === 'IHDR') {
            header = { width: body.readUInt32BE(0), height: body.readUInt32BE(4), depth: body[8], color: body[9], interlace: body[12] };
        } else if (type === 'IDAT') data.push(body);
        else if (type === 'IEND') break;
        offset += 12 + length;
    }
    if (!header) throw new Error('PNG without IHDR');
    const channels = kChannels[header.color];
    if (header.depth !== 8 || !channels || header.interlace !== 0) {
        throw new Error(`PNG bit depth ${header.depth}, color type ${header.color}, interlace ${header.interlace} is not read here`);
    }
    const { width, height } = header;
    const raw = zlib.inflateSync(Buffer.concat(data));
    const stride = width * channels;
    const pixels = new Uint8Array(height * stride);
    for (let y = 0; y < height; ++y) {
        const filter = raw[y * (stride + 1)];
        const line = raw.subarray(y * (stride + 1) + 1, (y + 1) * (stride + 1));
        const row = y * stride;
        for (let x = 0; x < stride; ++x) {
            const a = x >= channels ? pixels[row + x - channels] : 0;
            const b = y > 0 ? pixels[row - stride + x] : 0;
            const c = x >= channels && y > 0 ? pixels[row - stride + x - channels] : 0;
            let predictor = 0;
            if (filter === 1) predictor = a;
            else if (filter === 2) predictor = b;
            else if (filter === 3) predictor = (a + b) >> 1;
            else if (filter === 4) {
                const p = a + b - c, pa = Math.abs(p - a), pb = Math.abs(p - b), pc = Math.abs(p - c);
                predictor = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
            } else if (filter !== 0) throw new Error(`PNG filter ${filter}`);
            pixels[row + x] = (line[x] + predictor) & 0xff;
        }
    }
    const rgb = new Uint8Array(width * height * 3);
    for (let i = 0; i < width * height; ++i) {
        for (let k = 0; k < 3; ++k) rgb[i * 3 + k] = pixels[i * channels + (channels < 3 ? 0 : k)];
    }
    return { width, height, rgb };
}

const kCrcTable = Array.from({ length: 256 }, (_, n) => {
    let c = n;
    for (let k = 0; k < 8; ++k) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
    return c >>> 0;
});
function crc32(buffer) {
    let c = 0xffffffff;
    for (const byte of buffer) c = kCrcTable[(c ^ byte) & 0xff] ^ (c >>> 8);
    return (c ^ 0xffffffff) >>> 0;
}
function chunk(type, body) {
    const out = Buffer.alloc(12 + body.length);
    out.writeUInt32BE(body.length, 0);
    out.write(type, 4, 'latin1');
    body.copy(out, 8);
    out.writeUInt32BE(crc32(out.subarray(4, 8 + body.length)), 8 + body.length);
    return out;
}

// An RGB PNG of `rgb` (width * height * 3 bytes, rows top to bottom).
export function encodePng(width, height, rgb) {
    const header = Buffer.alloc(13);
    header.writeUInt32BE(width, 0);
    header.writeUInt32BE(height, 4);
    header[8] = 8;
    header[9] = 2;
    const raw = Buffer.alloc(height * (width * 3 + 1));
    for (let y = 0; y < height; ++y) Buffer.from(rgb.buffer, rgb.byteOffset + y * width * 3, width * 3).copy(raw, y * (width * 3 + 1) + 1);
    return Buffer.concat([kSignature, chunk('IHDR', header), chunk('IDAT', zlib.deflateSync(raw)), chunk('IEND', Buffer.alloc(0))]);
}
