//! A small HDF5 writer: superblock v0, datasets with version-1 object
//! headers and contiguous storage, groups as HDF 1.8 "new style" groups
//! (version-2 header, link messages, creation order tracked) — the flavour
//! the MED library writes and expects, read by every HDF5 since 1.8, and so
//! by MED, Salome and ParaView.
//!
//! A file is built as a tree of [`Node`]s and serialised in one pass,
//! children before parents, so every address is known when it is written.

/// Element types that can be written.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum WType {
    I32,
    I64,
    F64,
    /// NUL-terminated string of this many bytes (terminator included).
    Str(usize),
    /// Array of `n` signed bytes: how MED 3+ stores fixed-width names.
    I8Array(usize),
}

impl WType {
    fn size(self) -> usize {
        match self {
            WType::I32 => 4,
            WType::I64 | WType::F64 => 8,
            WType::Str(n) | WType::I8Array(n) => n,
        }
    }

    fn encode(self) -> Vec<u8> {
        let mut b = Vec::new();
        match self {
            WType::I32 | WType::I64 => {
                let size = self.size() as u32;
                b.extend([0x10, 0x08, 0, 0]);
                b.extend(size.to_le_bytes());
                b.extend(0u16.to_le_bytes());
                b.extend(((size * 8) as u16).to_le_bytes());
            }
            WType::F64 => {
                b.extend([0x11, 0x20, 63, 0]);
                b.extend(8u32.to_le_bytes());
                b.extend(0u16.to_le_bytes());
                b.extend(64u16.to_le_bytes());
                b.extend([52, 11, 0, 52]);
                b.extend(1023u32.to_le_bytes());
            }
            WType::Str(n) => {
                b.extend([0x13, 0, 0, 0]);
                b.extend((n as u32).to_le_bytes());
            }
            WType::I8Array(n) => {
                b.extend([0x2a, 0, 0, 0]);
                b.extend((n as u32).to_le_bytes());
                b.extend([1, 0, 0, 0]);
                b.extend((n as u32).to_le_bytes());
                b.extend(0u32.to_le_bytes()); // permutation index
                b.extend([0x10, 0x08, 0, 0]);
                b.extend(1u32.to_le_bytes());
                b.extend(0u16.to_le_bytes());
                b.extend(8u16.to_le_bytes());
            }
        }
        b
    }
}

/// An attribute to write: scalar when `dims` is empty.
#[derive(Clone, Debug)]
pub struct WAttr {
    pub name: String,
    pub ty: WType,
    pub dims: Vec<u64>,
    pub data: Vec<u8>,
}

impl WAttr {
    pub fn int(name: &str, v: i32) -> WAttr {
        WAttr {
            name: name.into(),
            ty: WType::I32,
            dims: vec![],
            data: v.to_le_bytes().to_vec(),
        }
    }

    pub fn float(name: &str, v: f64) -> WAttr {
        WAttr {
            name: name.into(),
            ty: WType::F64,
            dims: vec![],
            data: v.to_le_bytes().to_vec(),
        }
    }

    pub fn string(name: &str, v: &str) -> WAttr {
        let mut data = v.as_bytes().to_vec();
        data.push(0);
        WAttr {
            name: name.into(),
            ty: WType::Str(data.len()),
            dims: vec![],
            data,
        }
    }
}

/// A group or dataset to write.
#[derive(Clone, Debug)]
pub enum Node {
    Group {
        name: String,
        attrs: Vec<WAttr>,
        children: Vec<Node>,
    },
    Dataset {
        name: String,
        attrs: Vec<WAttr>,
        ty: WType,
        dims: Vec<u64>,
        /// Little-endian element bytes, row-major.
        data: Vec<u8>,
    },
}

impl Node {
    /// About the bytes this node takes in the file: its data, alignment and
    /// an allowance for its header, messages and attributes.
    fn size_hint(&self) -> usize {
        let header = |attrs: &[WAttr]| 256 + 64 * attrs.len();
        match self {
            Node::Group {
                attrs, children, ..
            } => {
                header(attrs)
                    + children
                        .iter()
                        .map(|c| 48 + c.name().len() + c.size_hint())
                        .sum::<usize>()
            }
            Node::Dataset { attrs, data, .. } => header(attrs) + pad8(data.len()),
        }
    }

    pub fn group(name: &str, attrs: Vec<WAttr>, children: Vec<Node>) -> Node {
        Node::Group {
            name: name.into(),
            attrs,
            children,
        }
    }

    pub fn i32s(name: &str, attrs: Vec<WAttr>, values: &[i32]) -> Node {
        let mut data = Vec::with_capacity(values.len() * 4);
        for v in values {
            data.extend_from_slice(&v.to_le_bytes());
        }
        Node::Dataset {
            name: name.into(),
            attrs,
            ty: WType::I32,
            dims: vec![values.len() as u64],
            data,
        }
    }

    pub fn f64s(name: &str, attrs: Vec<WAttr>, values: &[f64]) -> Node {
        let mut data = Vec::with_capacity(values.len() * 8);
        for v in values {
            data.extend_from_slice(&v.to_le_bytes());
        }
        Node::Dataset {
            name: name.into(),
            attrs,
            ty: WType::F64,
            dims: vec![values.len() as u64],
            data,
        }
    }

    /// Fixed-width names as an `i8[width]` array per name (MED 3+ style).
    pub fn names(name: &str, attrs: Vec<WAttr>, names: &[String], width: usize) -> Node {
        let mut data = vec![0u8; names.len() * width];
        for (i, n) in names.iter().enumerate() {
            let b = n.as_bytes();
            let k = b.len().min(width);
            data[i * width..i * width + k].copy_from_slice(&b[..k]);
        }
        Node::Dataset {
            name: name.into(),
            attrs,
            ty: WType::I8Array(width),
            dims: vec![names.len() as u64],
            data,
        }
    }

    fn name(&self) -> &str {
        match self {
            Node::Group { name, .. } | Node::Dataset { name, .. } => name,
        }
    }
}

const UNDEF: u64 = u64::MAX;
/// B-tree parameters announced by the superblock (HDF5's defaults; no
/// symbol-table group is written).
const LEAF_K: usize = 4;
const NODE_K: usize = 16;

/// Serialise a root group (its own name is ignored) to an HDF5 file image.
pub fn to_bytes(root: &Node) -> Vec<u8> {
    // The file's size, about: data, padding and headers. Reserved at once,
    // the buffer is not copied as it grows (a 191 kB result file took 15 %
    // of a one-element case's time, most of it in reallocations).
    let mut buf = Vec::with_capacity(96 + root.size_hint());
    buf.resize(96, 0);
    let mut w = Writer { buf };
    let (addr, _) = w.object(root);
    let eof = w.buf.len() as u64;
    let mut sb = Vec::with_capacity(96);
    sb.extend([0x89, b'H', b'D', b'F', b'\r', b'\n', 0x1a, b'\n']);
    sb.extend([0, 0, 0, 0, 0, 8, 8, 0]);
    sb.extend((LEAF_K as u16).to_le_bytes());
    sb.extend((NODE_K as u16).to_le_bytes());
    sb.extend(0u32.to_le_bytes());
    for v in [0, UNDEF, eof, UNDEF] {
        sb.extend(v.to_le_bytes());
    }
    // Root symbol table entry: no cached symbol table (the root is a new-style group).
    sb.extend(0u64.to_le_bytes());
    sb.extend(addr.to_le_bytes());
    sb.extend([0u8; 24]);
    w.buf[..96].copy_from_slice(&sb);
    w.buf
}

struct Writer {
    buf: Vec<u8>,
}

fn pad8(n: usize) -> usize {
    n.div_ceil(8) * 8
}

impl Writer {
    fn align(&mut self) {
        let n = pad8(self.buf.len());
        self.buf.resize(n, 0);
    }

    fn here(&self) -> u64 {
        self.buf.len() as u64
    }

    /// Write an object and what it needs; returns its header address.
    fn object(&mut self, node: &Node) -> (u64, ()) {
        match node {
            Node::Dataset {
                attrs,
                ty,
                dims,
                data,
                ..
            } => {
                self.align();
                let addr = if data.is_empty() { UNDEF } else { self.here() };
                self.buf.extend_from_slice(data);
                let mut msgs = vec![
                    (0x01u16, dataspace(dims)),
                    (0x03, ty.encode()),
                    (0x08, {
                        let mut l = vec![3u8, 1];
                        l.extend(addr.to_le_bytes());
                        l.extend((data.len() as u64).to_le_bytes());
                        l
                    }),
                ];
                msgs.extend(attrs.iter().map(|a| (0x0C, attribute(a))));
                (self.header(&msgs), ())
            }
            Node::Group {
                attrs, children, ..
            } => {
                // "New style" group: links as messages of a version-2
                // header, creation order tracked. The MED library (≥ 3)
                // lists a group's members by creation order and fails on
                // symbol-table groups of files that claim MED ≥ 3.
                let entries: Vec<(&str, u64)> = children
                    .iter()
                    .map(|c| (c.name(), self.object(c).0))
                    .collect();
                let mut msgs = Vec::with_capacity(entries.len() + attrs.len() + 2);
                let mut linfo = vec![0u8, 0x01];
                linfo.extend((entries.len() as u64).to_le_bytes());
                linfo.extend(UNDEF.to_le_bytes());
                linfo.extend(UNDEF.to_le_bytes());
                msgs.push((0x02u16, linfo));
                msgs.push((0x0A, vec![0u8, 0]));
                for (order, (name, addr)) in entries.iter().enumerate() {
                    let name = name.as_bytes();
                    let wide = name.len() > 255;
                    let mut l = vec![1u8, 0x04 | wide as u8];
                    l.extend((order as u64).to_le_bytes());
                    if wide {
                        l.extend((name.len() as u16).to_le_bytes());
                    } else {
                        l.push(name.len() as u8);
                    }
                    l.extend_from_slice(name);
                    l.extend(addr.to_le_bytes());
                    msgs.push((0x06, l));
                }
                msgs.extend(attrs.iter().map(|a| (0x0C, attribute(a))));
                (self.header_v2(&msgs), ())
            }
        }
    }

    /// A version-2 object header (`OHDR`, lookup3 checksum) holding these messages.
    fn header_v2(&mut self, msgs: &[(u16, Vec<u8>)]) -> u64 {
        self.align();
        let at = self.here();
        let start = self.buf.len();
        let size: usize = msgs.iter().map(|(_, b)| 4 + b.len()).sum();
        self.buf.extend_from_slice(b"OHDR");
        self.buf.extend([2, 0x02]);
        self.buf.extend((size as u32).to_le_bytes());
        for (ty, body) in msgs {
            self.buf.push(*ty as u8);
            self.buf.extend((body.len() as u16).to_le_bytes());
            self.buf.push(0);
            self.buf.extend_from_slice(body);
        }
        let sum = super::checksum::lookup3(&self.buf[start..]);
        self.buf.extend(sum.to_le_bytes());
        at
    }

    /// A version-1 object header holding these messages.
    fn header(&mut self, msgs: &[(u16, Vec<u8>)]) -> u64 {
        self.align();
        let at = self.here();
        let size: usize = msgs.iter().map(|(_, b)| 8 + pad8(b.len())).sum();
        self.buf.extend([1, 0]);
        self.buf.extend((msgs.len() as u16).to_le_bytes());
        self.buf.extend(1u32.to_le_bytes());
        self.buf.extend((size as u32).to_le_bytes());
        self.buf.extend([0u8; 4]);
        for (ty, body) in msgs {
            self.buf.extend(ty.to_le_bytes());
            self.buf.extend((pad8(body.len()) as u16).to_le_bytes());
            self.buf.extend([0u8; 4]);
            self.buf.extend_from_slice(body);
            let n = pad8(self.buf.len());
            self.buf.resize(n, 0);
        }
        at
    }
}

fn dataspace(dims: &[u64]) -> Vec<u8> {
    let mut b = vec![1, dims.len() as u8, 0, 0, 0, 0, 0, 0];
    for d in dims {
        b.extend(d.to_le_bytes());
    }
    b
}

fn attribute(a: &WAttr) -> Vec<u8> {
    let name_len = a.name.len() + 1;
    let dt = a.ty.encode();
    let ds = dataspace(&a.dims);
    let mut b = vec![1, 0];
    b.extend((name_len as u16).to_le_bytes());
    b.extend((dt.len() as u16).to_le_bytes());
    b.extend((ds.len() as u16).to_le_bytes());
    b.extend(a.name.as_bytes());
    b.resize(8 + pad8(name_len), 0);
    let n = b.len();
    b.extend(&dt);
    b.resize(n + pad8(dt.len()), 0);
    let n = b.len();
    b.extend(&ds);
    b.resize(n + pad8(ds.len()), 0);
    b.extend(&a.data);
    b
}
