//! A small HDF5 writer: the oldest, most widely readable flavour of the
//! format (superblock v0, object headers v1, symbol-table groups,
//! contiguous datasets), which every HDF5 library since 1.6 reads — and so
//! MED, Salome and ParaView.
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
/// Symbols per symbol-table node (2 × group leaf K, K = 4).
const LEAF_K: usize = 4;
/// Children per group B-tree node (2 × group internal K, K = 16).
const NODE_K: usize = 16;

/// Serialise a root group (its own name is ignored) to an HDF5 file image.
pub fn to_bytes(root: &Node) -> Vec<u8> {
    let mut w = Writer { buf: vec![0; 96] };
    let (addr, stab) = w.object(root);
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
    // Root symbol table entry, caching the root's B-tree and heap.
    sb.extend(0u64.to_le_bytes());
    sb.extend(addr.to_le_bytes());
    let (btree, heap) = stab.unwrap_or((UNDEF, UNDEF));
    sb.extend(1u32.to_le_bytes());
    sb.extend(0u32.to_le_bytes());
    sb.extend(btree.to_le_bytes());
    sb.extend(heap.to_le_bytes());
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

    /// Write an object and what it needs; returns its header address and,
    /// for groups, (B-tree, heap) addresses.
    fn object(&mut self, node: &Node) -> (u64, Option<(u64, u64)>) {
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
                (self.header(&msgs), None)
            }
            Node::Group {
                attrs, children, ..
            } => {
                let mut entries: Vec<(&str, u64)> = children
                    .iter()
                    .map(|c| (c.name(), self.object(c).0))
                    .collect();
                entries.sort_by(|a, b| a.0.as_bytes().cmp(b.0.as_bytes()));
                // Local heap: offset 0 is the empty string.
                let mut heap = vec![0u8; 8];
                let mut offsets = Vec::with_capacity(entries.len());
                for (name, _) in &entries {
                    offsets.push(heap.len() as u64);
                    heap.extend_from_slice(name.as_bytes());
                    heap.push(0);
                    heap.resize(pad8(heap.len()), 0);
                }
                self.align();
                let heap_data = self.here();
                self.buf.extend_from_slice(&heap);
                let heap_addr = self.here();
                self.buf.extend_from_slice(b"HEAP");
                self.buf.extend([0, 0, 0, 0]);
                self.buf.extend((heap.len() as u64).to_le_bytes());
                // No free block: HDF5 marks this with offset 1 (H5HL_FREE_NULL).
                self.buf.extend(1u64.to_le_bytes());
                self.buf.extend(heap_data.to_le_bytes());
                // Symbol nodes of up to 2K entries, each with the offset of its last name.
                let mut level: Vec<(u64, u64)> = Vec::new();
                let chunks: Vec<usize> = (0..entries.len()).step_by(2 * LEAF_K).collect();
                for &start in &chunks {
                    let end = (start + 2 * LEAF_K).min(entries.len());
                    self.align();
                    let at = self.here();
                    let base = self.buf.len();
                    self.buf.extend_from_slice(b"SNOD");
                    self.buf.extend([1, 0]);
                    self.buf.extend(((end - start) as u16).to_le_bytes());
                    for i in start..end {
                        self.buf.extend(offsets[i].to_le_bytes());
                        self.buf.extend(entries[i].1.to_le_bytes());
                        self.buf.extend([0u8; 24]);
                    }
                    self.buf.resize(base + 8 + 2 * LEAF_K * 40, 0);
                    level.push((at, offsets[end - 1]));
                }
                let btree = self.btree(level);
                let msgs = {
                    let mut s = btree.to_le_bytes().to_vec();
                    s.extend(heap_addr.to_le_bytes());
                    let mut m = vec![(0x11u16, s)];
                    m.extend(attrs.iter().map(|a| (0x0C, attribute(a))));
                    m
                };
                (self.header(&msgs), Some((btree, heap_addr)))
            }
        }
    }

    /// Build the group B-tree over (child address, last-name offset) pairs; returns the root.
    fn btree(&mut self, mut children: Vec<(u64, u64)>) -> u64 {
        let mut depth = 0u8;
        loop {
            let mut parents = Vec::new();
            let groups: Vec<&[(u64, u64)]> = if children.is_empty() {
                vec![&[][..]]
            } else {
                children.chunks(2 * NODE_K).collect()
            };
            let mut addrs = Vec::with_capacity(groups.len());
            let node_size = 24 + (2 * NODE_K + 1) * 8 + 2 * NODE_K * 8;
            for _ in &groups {
                self.align();
                addrs.push(self.here());
                let n = self.buf.len();
                self.buf.resize(n + node_size, 0);
            }
            for (i, g) in groups.iter().enumerate() {
                let mut b = Vec::with_capacity(node_size);
                b.extend_from_slice(b"TREE");
                b.extend([0, depth]);
                b.extend((g.len() as u16).to_le_bytes());
                let left = if i > 0 { addrs[i - 1] } else { UNDEF };
                let right = addrs.get(i + 1).copied().unwrap_or(UNDEF);
                b.extend(left.to_le_bytes());
                b.extend(right.to_le_bytes());
                b.extend(0u64.to_le_bytes());
                for (child, last) in g.iter() {
                    b.extend(child.to_le_bytes());
                    b.extend(last.to_le_bytes());
                }
                let at = addrs[i] as usize;
                self.buf[at..at + b.len()].copy_from_slice(&b);
                parents.push((addrs[i], g.last().map_or(0, |c| c.1)));
            }
            if parents.len() == 1 {
                return parents[0].0;
            }
            children = parents;
            depth += 1;
        }
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
