//! A zlib stream (RFC 1950) of one small buffer, deflated (RFC 1951) in one block of the
//! fixed Huffman codes: what [`VtkFormat::Compressed`](crate::VtkFormat) writes for each
//! block of a data array.
//!
//! Why not a zlib library: a path's frames are many small arrays (the 300-bearing beam's 624
//! frames, about 11 000 arrays of a few kilobytes), each its own zlib stream, as VTK reads
//! them. `zlib-rs` at its fastest level clears a hash table of 128 KB for every stream, more
//! bytes than the array itself, and its encoder was a quarter of such a run
//! (`docs/performance.md`, round 36). This encoder keeps a thread's table from stream to
//! stream: an entry holds a position counted over all the thread's streams, so the entries
//! of earlier streams are below the current stream's start and are never taken — the output
//! depends on the bytes alone, whichever thread writes them.
//!
//! The matches are found as LZ4 finds them: a hash of the next four bytes, one candidate,
//! no chains; where no match is found for a while the search steps further at a time, so that
//! data that does not compress costs little. A block that would come out larger than its
//! bytes in stored blocks (with their 5-byte headers) is stored instead.

use std::cell::RefCell;

/// log2 of the hash table's entries.
const HASH_BITS: u32 = 14;
/// Deflate's window: a match reaches at most this far back.
const WINDOW: usize = 32_768;
/// The shortest match looked for (deflate allows 3; four bytes are one load).
const MIN_MATCH: usize = 4;
/// Deflate's longest match.
const MAX_MATCH: usize = 258;

/// The bits of `code` (of `len` bits) in reverse order: deflate writes a Huffman code from its
/// first bit into a stream filled from each byte's lowest bit.
const fn reverse(code: u32, len: u32) -> u32 {
    let mut r = 0;
    let mut k = 0;
    while k < len {
        r |= ((code >> k) & 1) << (len - 1 - k);
        k += 1;
    }
    r
}

/// The fixed literal/length code of symbol `s` (RFC 1951, 3.2.6): `(bits as written, length)`.
const fn fixed_code(s: u32) -> (u32, u32) {
    let (code, len) = if s <= 143 {
        (0x30 + s, 8)
    } else if s <= 255 {
        (0x190 + s - 144, 9)
    } else if s <= 279 {
        (s - 256, 7)
    } else {
        (0xc0 + s - 280, 8)
    };
    (reverse(code, len), len)
}

/// A literal's code: `(bits, length)` for each byte value.
const LITERALS: [(u32, u32); 256] = {
    let mut t = [(0, 0); 256];
    let mut b = 0;
    while b < 256 {
        t[b] = fixed_code(b as u32);
        b += 1;
    }
    t
};

/// The first length of each length symbol 257 … 285, and its extra bits.
const LENGTH_BASE: [u32; 29] = [
    3, 4, 5, 6, 7, 8, 9, 10, 11, 13, 15, 17, 19, 23, 27, 31, 35, 43, 51, 59, 67, 83, 99, 115, 131,
    163, 195, 227, 258,
];
const LENGTH_EXTRA: [u32; 29] = [
    0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0,
];

/// A match length's whole code, its symbol's code then its extra bits: `(bits, length)` for
/// each length 0 … 258 (0 … 2 unused).
const LENGTHS: [(u32, u32); MAX_MATCH + 1] = {
    let mut t = [(0, 0); MAX_MATCH + 1];
    let mut len = 3;
    while len <= MAX_MATCH {
        // The last symbol whose base is at most `len`: 258 as symbol 285, as zlib writes it.
        let mut k = 28;
        while LENGTH_BASE[k] > len as u32 {
            k -= 1;
        }
        let (code, bits) = fixed_code(257 + k as u32);
        let extra = len as u32 - LENGTH_BASE[k];
        t[len] = (code | (extra << bits), bits + LENGTH_EXTRA[k]);
        len += 1;
    }
    t
};

/// The first distance of each distance code 0 … 29, and its extra bits.
const DIST_BASE: [u32; 30] = [
    1, 2, 3, 4, 5, 7, 9, 13, 17, 25, 33, 49, 65, 97, 129, 193, 257, 385, 513, 769, 1025, 1537,
    2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577,
];
const DIST_EXTRA: [u32; 30] = [
    0, 0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 5, 5, 6, 6, 7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13,
    13,
];

/// Each distance code as written (its five bits reversed).
const DIST_CODES: [u32; 30] = {
    let mut t = [0; 30];
    let mut k = 0;
    while k < 30 {
        t[k] = reverse(k as u32, 5);
        k += 1;
    }
    t
};

/// The distance code of distance `d` (1 … 32 768).
fn dist_code(d: u32) -> usize {
    // The codes double their span every two codes: from the position of the highest bit of
    // `d − 1` and the bit below it.
    if d <= 4 {
        (d - 1) as usize
    } else {
        let x = d - 1;
        let top = 31 - x.leading_zeros();
        (2 * top + ((x >> (top - 1)) & 1)) as usize
    }
}

/// Bits written from each byte's lowest bit.
struct Bits {
    out: Vec<u8>,
    acc: u64,
    n: u32,
}

impl Bits {
    /// Appends the `len` low bits of `bits` (`len` ≤ 32).
    #[inline(always)]
    fn put(&mut self, bits: u32, len: u32) {
        self.acc |= u64::from(bits) << self.n;
        self.n += len;
        if self.n >= 32 {
            self.out.extend_from_slice(&(self.acc as u32).to_le_bytes());
            self.acc >>= 32;
            self.n -= 32;
        }
    }

    /// The bits written so far, the last byte filled with zeros.
    fn finish(mut self) -> Vec<u8> {
        while self.n > 0 {
            self.out.push(self.acc as u8);
            self.acc >>= 8;
            self.n = self.n.saturating_sub(8);
        }
        self.out
    }

    fn literals(&mut self, bytes: &[u8]) {
        // Two at a time: at most 18 bits.
        let mut pairs = bytes.chunks_exact(2);
        for p in &mut pairs {
            let (a, la) = LITERALS[p[0] as usize];
            let (b, lb) = LITERALS[p[1] as usize];
            self.put(a | (b << la), la + lb);
        }
        for &b in pairs.remainder() {
            let (c, l) = LITERALS[b as usize];
            self.put(c, l);
        }
    }

    /// A match of `len` bytes (3 … 258) at distance `dist` (1 … 32 768): at most 31 bits.
    #[inline(always)]
    fn matched(&mut self, len: usize, dist: u32) {
        let (lc, ll) = LENGTHS[len];
        let k = dist_code(dist);
        let dc = DIST_CODES[k] | ((dist - DIST_BASE[k]) << 5);
        self.put(lc | (dc << ll), ll + 5 + DIST_EXTRA[k]);
    }
}

#[inline(always)]
fn load4(bytes: &[u8], at: usize) -> u32 {
    u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap())
}

#[inline(always)]
fn hash(v: u32) -> usize {
    (v.wrapping_mul(2_654_435_761) >> (32 - HASH_BITS)) as usize
}

/// The number of equal bytes of `bytes[a..]` and `bytes[b..]` (`a < b`), at most `max`.
#[inline(always)]
fn common(bytes: &[u8], a: usize, b: usize, max: usize) -> usize {
    let mut n = 0;
    while n + 8 <= max {
        let x = u64::from_le_bytes(bytes[a + n..a + n + 8].try_into().unwrap());
        let y = u64::from_le_bytes(bytes[b + n..b + n + 8].try_into().unwrap());
        let d = x ^ y;
        if d != 0 {
            return n + (d.trailing_zeros() / 8) as usize;
        }
        n += 8;
    }
    while n < max && bytes[a + n] == bytes[b + n] {
        n += 1;
    }
    n
}

/// A thread's hash table and the count of the bytes of its earlier streams.
struct Table {
    heads: Box<[u32]>,
    /// The first position of the next stream: every entry below it is an earlier stream's.
    base: u32,
}

impl Table {
    fn new() -> Self {
        Self {
            heads: vec![0; 1 << HASH_BITS].into_boxed_slice(),
            base: 1,
        }
    }

    /// `bytes` as one zlib stream.
    fn zlib(&mut self, bytes: &[u8]) -> Vec<u8> {
        let n = bytes.len();
        if n > (u32::MAX / 4) as usize {
            // Positions would not fit the table's counts (never met: a block is 32 KB).
            return stored(bytes);
        }
        // The fixed codes take at most 9 bits a byte.
        let mut out = Vec::with_capacity(n + n / 8 + 16);
        // CMF: deflate, a 32 KB window; FLG: the fastest level, no dictionary, a multiple of 31.
        out.extend_from_slice(&[0x78, 0x01]);
        let mut w = Bits { out, acc: 0, n: 0 };
        // The last block, of the fixed codes.
        w.put(0b011, 3);
        if u64::from(self.base) + n as u64 >= u64::from(u32::MAX) {
            // Positions counted afresh: no entry may look like one of this stream's.
            self.heads.fill(0);
            self.base = 1;
        }
        deflate_into(&mut w, bytes, &mut self.heads, self.base);
        self.base += n as u32;
        let (end, len) = fixed_code(256);
        w.put(end, len);
        let mut out = w.finish();
        if out.len() > stored_len(n) {
            return stored(bytes);
        }
        out.extend_from_slice(&adler32(bytes).to_be_bytes());
        out
    }
}

thread_local! {
    static TABLE: RefCell<Table> = RefCell::new(Table::new());
}

/// `bytes` as one zlib stream (RFC 1950: a header, the deflated bytes, their Adler-32),
/// inflated by any zlib: one compressed block of a `.vtu` data array.
pub fn zlib(bytes: &[u8]) -> Vec<u8> {
    TABLE.with(|t| t.borrow_mut().zlib(bytes))
}

/// The matches and literals of `bytes`, positions in `heads` counted from `base`.
fn deflate_into(w: &mut Bits, bytes: &[u8], heads: &mut [u32], base: u32) {
    let n = bytes.len();
    let mut lit = 0;
    if n >= MIN_MATCH {
        let last = n - MIN_MATCH;
        let mut i = 0;
        let mut misses = 1u32 << 6;
        while i <= last {
            let v = load4(bytes, i);
            let h = hash(v);
            let cand = heads[h];
            heads[h] = base + i as u32;
            if cand >= base {
                let c = (cand - base) as usize;
                if i - c <= WINDOW && load4(bytes, c) == v {
                    let len = MIN_MATCH
                        + common(
                            bytes,
                            c + MIN_MATCH,
                            i + MIN_MATCH,
                            (n - i - MIN_MATCH).min(MAX_MATCH - MIN_MATCH),
                        );
                    w.literals(&bytes[lit..i]);
                    w.matched(len, (i - c) as u32);
                    i += len;
                    lit = i;
                    misses = 1 << 6;
                    // The position two before the match's end, as LZ4 does.
                    if i - 2 <= last {
                        heads[hash(load4(bytes, i - 2))] = base + (i - 2) as u32;
                    }
                    continue;
                }
            }
            i += (misses >> 6) as usize;
            misses += 1;
        }
    }
    w.literals(&bytes[lit..]);
}

/// The size of `n` bytes in stored blocks, with the zlib header (the checksum apart).
fn stored_len(n: usize) -> usize {
    2 + n + 5 * n.div_ceil(65_535).max(1)
}

/// `bytes` as one zlib stream of stored blocks.
fn stored(bytes: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(stored_len(bytes.len()) + 4);
    out.extend_from_slice(&[0x78, 0x01]);
    let mut chunks = bytes.chunks(65_535).peekable();
    if chunks.peek().is_none() {
        out.extend_from_slice(&[1, 0, 0, 0xff, 0xff]);
    }
    while let Some(c) = chunks.next() {
        let last = u8::from(chunks.peek().is_none());
        let len = c.len() as u16;
        out.push(last);
        out.extend_from_slice(&len.to_le_bytes());
        out.extend_from_slice(&(!len).to_le_bytes());
        out.extend_from_slice(c);
    }
    out.extend_from_slice(&adler32(bytes).to_be_bytes());
    out
}

/// The Adler-32 checksum of `bytes` (RFC 1950, 8.2).
fn adler32(bytes: &[u8]) -> u32 {
    zlib_rs::adler32::adler32(1, bytes)
}

#[cfg(test)]
mod tests {
    use super::{stored_len, zlib, Table};
    use crate::replay::bits;
    use proptest::prelude::*;

    /// The Adler-32 of RFC 1950 as its text gives it, a byte at a time.
    fn adler_by_the_rfc(bytes: &[u8]) -> u32 {
        let (mut a, mut b) = (1u32, 0u32);
        for &x in bytes {
            a = (a + u32::from(x)) % 65_521;
            b = (b + a) % 65_521;
        }
        (b << 16) | a
    }

    /// The stream inflated by another implementation (`miniz_oxide`, which checks the
    /// header and the checksum), and its checksum by the RFC's definition.
    fn assert_round_trip(stream: &[u8], bytes: &[u8]) {
        assert_eq!(&stream[..2], &[0x78, 0x01], "the zlib header");
        assert_eq!(u16::from_be_bytes([stream[0], stream[1]]) % 31, 0);
        let back = miniz_oxide::inflate::decompress_to_vec_zlib(stream)
            .unwrap_or_else(|e| panic!("not inflated: {e:?} ({} bytes)", bytes.len()));
        assert!(back == bytes, "{} bytes inflated differ", bytes.len());
        let sum = u32::from_be_bytes(stream[stream.len() - 4..].try_into().unwrap());
        assert_eq!(sum, adler_by_the_rfc(bytes));
    }

    /// Short inputs at every length (no match possible below four bytes), runs, the values
    /// of a frame's arrays, and bytes that do not compress (stored, as small as stored can
    /// be); a long run takes the longest matches (a few bytes for 32 KB).
    #[test]
    fn blocks_of_every_kind_inflate_to_their_bytes() {
        let pattern: Vec<u8> = (0..400u32).map(|k| (k * k % 7) as u8).collect();
        for n in 0..=400 {
            assert_round_trip(&zlib(&pattern[..n]), &pattern[..n]);
        }
        let zeros = vec![0u8; 32_768];
        let z = zlib(&zeros);
        assert_round_trip(&z, &zeros);
        assert!(z.len() < 240, "{} bytes for 32 KB of zeros", z.len());
        let mut next = bits(3);
        let noise: Vec<u8> = (0..32_768).map(|_| next() as u8).collect();
        let z = zlib(&noise);
        assert_round_trip(&z, &noise);
        assert_eq!(z.len(), stored_len(noise.len()) + 4, "stored");
        // A frame's kinds of arrays: doubles of a smooth field, indices, small codes.
        let field: Vec<u8> = (0..4096)
            .flat_map(|k| (1e-3 * (f64::from(k) * 0.01).sin()).to_le_bytes())
            .collect();
        let ints: Vec<u8> = (0..4096i64).flat_map(|k| (k / 2).to_le_bytes()).collect();
        let codes: Vec<u8> = (0..8192i32)
            .flat_map(|k| (k % 5 / 4).to_le_bytes())
            .collect();
        // Full-precision doubles hardly compress (at most stored); the indices and codes do.
        let z = zlib(&field);
        assert_round_trip(&z, &field);
        assert!(z.len() <= stored_len(field.len()) + 4);
        for bytes in [&ints, &codes] {
            let z = zlib(bytes);
            assert_round_trip(&z, bytes);
            assert!(z.len() < bytes.len() / 3, "{} of {}", z.len(), bytes.len());
        }
        // Longer than the window and than a stored block (65 535 bytes): matches reach only
        // 32 KB back, bytes that do not compress go into three stored blocks.
        let mut long = noise.clone();
        long.extend_from_slice(&field[..20_000]);
        long.extend_from_slice(&noise);
        long.extend_from_slice(&noise[..10_000]);
        assert_round_trip(&zlib(&long), &long);
        let mut next = bits(5);
        let wide: Vec<u8> = (0..150_000).map(|_| next() as u8).collect();
        assert_round_trip(&zlib(&wide), &wide);
    }

    /// A stream's bytes depend on its input alone: not on the streams the thread compressed
    /// before (whose entries stay in the table), nor on where the table's count is, up to
    /// its renewal when the count would pass `u32::MAX`.
    #[test]
    fn a_stream_does_not_depend_on_the_streams_before_it() {
        let a: Vec<u8> = (0..20_000u32)
            .map(|k| ((k % 251) ^ (k / 97)) as u8)
            .collect();
        let b: Vec<u8> = (0..20_000u32)
            .map(|k| ((k % 241) ^ (k / 89)) as u8)
            .collect();
        let alone = Table::new().zlib(&b);
        let mut t = Table::new();
        t.zlib(&a);
        t.zlib(&a);
        assert_eq!(t.zlib(&b), alone);
        for before in [30_000u32, 20_000, 10] {
            let mut t = Table::new();
            t.zlib(&a);
            t.base = u32::MAX - before;
            assert_eq!(t.zlib(&b), alone, "count {before} below the limit");
            assert_eq!(t.zlib(&b), alone, "after it");
        }
    }

    /// Bytes made of runs, copies from earlier and noise, at lengths up to two blocks.
    fn mixed() -> impl Strategy<Value = Vec<u8>> {
        prop::collection::vec((0u8..3, any::<u64>(), 1usize..600), 0..120).prop_map(|parts| {
            let mut out: Vec<u8> = Vec::new();
            for (kind, seed, len) in parts {
                match kind {
                    0 => out.extend(std::iter::repeat_n(seed as u8, len)),
                    1 if !out.is_empty() => {
                        let from = (seed as usize) % out.len();
                        for k in 0..len {
                            out.push(out[from + k]);
                        }
                    }
                    _ => {
                        let mut next = bits(seed);
                        out.extend((0..len).map(|_| next() as u8 & 0x3f));
                    }
                }
            }
            out
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]
        #[test]
        fn mixed_bytes_inflate_to_themselves(bytes in mixed()) {
            assert_round_trip(&zlib(&bytes), &bytes);
        }
    }
}
