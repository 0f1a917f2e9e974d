//! Jenkins' lookup3 `hashlittle`, the checksum of HDF5's version-2 metadata
//! (object headers `OHDR`, B-trees v2, heaps…), with initial value 0.

pub fn lookup3(data: &[u8]) -> u32 {
    let mut a: u32 = 0xdead_beef_u32.wrapping_add(data.len() as u32);
    let mut b = a;
    let mut c = a;
    let word = |k: &[u8], i: usize| -> u32 {
        (0..4)
            .map(|j| (k.get(i + j).copied().unwrap_or(0) as u32) << (8 * j))
            .fold(0, |x, y| x.wrapping_add(y))
    };
    let mut k = data;
    while k.len() > 12 {
        a = a.wrapping_add(word(k, 0));
        b = b.wrapping_add(word(k, 4));
        c = c.wrapping_add(word(k, 8));
        // mix
        a = a.wrapping_sub(c);
        a ^= c.rotate_left(4);
        c = c.wrapping_add(b);
        b = b.wrapping_sub(a);
        b ^= a.rotate_left(6);
        a = a.wrapping_add(c);
        c = c.wrapping_sub(b);
        c ^= b.rotate_left(8);
        b = b.wrapping_add(a);
        a = a.wrapping_sub(c);
        a ^= c.rotate_left(16);
        c = c.wrapping_add(b);
        b = b.wrapping_sub(a);
        b ^= a.rotate_left(19);
        a = a.wrapping_add(c);
        c = c.wrapping_sub(b);
        c ^= b.rotate_left(4);
        b = b.wrapping_add(a);
        k = &k[12..];
    }
    if k.is_empty() {
        return c;
    }
    // The last 1..=12 bytes, zero-padded.
    a = a.wrapping_add(word(k, 0));
    b = b.wrapping_add(word(k, 4));
    c = c.wrapping_add(word(k, 8));
    // final
    c ^= b;
    c = c.wrapping_sub(b.rotate_left(14));
    a ^= c;
    a = a.wrapping_sub(c.rotate_left(11));
    b ^= a;
    b = b.wrapping_sub(a.rotate_left(25));
    c ^= b;
    c = c.wrapping_sub(b.rotate_left(16));
    a ^= c;
    a = a.wrapping_sub(c.rotate_left(4));
    b ^= a;
    b = b.wrapping_sub(a.rotate_left(14));
    c ^= b;
    c = c.wrapping_sub(b.rotate_left(24));
    c
}

#[cfg(test)]
mod tests {
    use super::lookup3;

    #[test]
    fn known_values() {
        // From lookup3.c's self-test: hashlittle("", 0) = 0xdeadbeef,
        // hashlittle("Four score and seven years ago", 0) = 0x17770551.
        assert_eq!(lookup3(b""), 0xdead_beef);
        assert_eq!(lookup3(b"Four score and seven years ago"), 0x1777_0551);
    }

    #[test]
    fn matches_an_hdf5_object_header() {
        // The checksum of every OHDR block of a file written by the HDF5 library.
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/latest.h5");
        let data = std::fs::read(path).unwrap();
        assert!(check_all(&data) >= 5);
    }

    #[test]
    fn our_writer_checksums_its_group_headers() {
        use crate::hdf5::write::{to_bytes, Node, WAttr};
        let file = to_bytes(&Node::group(
            "",
            vec![],
            vec![
                Node::group(
                    "A",
                    vec![WAttr::int("N", 3)],
                    vec![Node::f64s("X", vec![], &[1.0, 2.0])],
                ),
                Node::group("B", vec![], vec![]),
            ],
        ));
        assert_eq!(check_all(&file), 3);
    }

    /// Verify the checksum of every `OHDR` block; returns how many were checked.
    fn check_all(data: &[u8]) -> usize {
        let mut checked = 0;
        let mut at = 0;
        while let Some(p) = data[at..].windows(4).position(|w| w == b"OHDR") {
            let start = at + p;
            let flags = data[start + 5];
            let mut pos = start + 6;
            if flags & 0x20 != 0 {
                pos += 16;
            }
            if flags & 0x10 != 0 {
                pos += 4;
            }
            let width = 1usize << (flags & 3);
            let size = (0..width).fold(0usize, |acc, j| acc | (data[pos + j] as usize) << (8 * j));
            let end = pos + width + size;
            if end + 4 <= data.len() {
                let stored =
                    u32::from_le_bytes([data[end], data[end + 1], data[end + 2], data[end + 3]]);
                assert_eq!(lookup3(&data[start..end]), stored, "OHDR at {start}");
                checked += 1;
            }
            at = start + 4;
        }
        checked
    }
}
