// Counter-based random numbers, bit for bit those of src/core/random.h, so that the browser plans
// the same trials as the app for the same seed. 64-bit arithmetic in BigInt.

const MASK = (1n << 64n) - 1n;
const u64 = (x) => x & MASK;

// SplitMix64's finaliser.
export function mix64(x) {
  x = u64(x + 0x9e3779b97f4a7c15n);
  x = u64((x ^ (x >> 30n)) * 0xbf58476d1ce4e5b9n);
  x = u64((x ^ (x >> 27n)) * 0x94d049bb133111ebn);
  return x ^ (x >> 31n);
}

export function hashCombine(a, b) {
  return mix64(u64(BigInt(a)) ^ mix64(u64(BigInt(b))));
}

// FNV-1a over the UTF-8 bytes of a string.
export function hashString(text) {
  let h = 1469598103934665603n;
  for (const byte of new TextEncoder().encode(text)) h = u64((h ^ BigInt(byte)) * 1099511628211n);
  return h;
}

// A stream of uniform numbers in [0, 1) keyed by (seed, domain, index, sample).
export class SampleStream {
  constructor(seed, domain, index, sample) {
    this.key = hashCombine(hashCombine(hashCombine(seed, domain), index), sample);
    this.counter = 0n;
  }

  next() {
    this.counter += 1n;
    const bits = mix64(u64(this.key + u64(0x632be59bd9b4e019n * this.counter))) >> 11n;
    return Number(bits) * 2 ** -53;
  }
}
