//! A compact, read-only HDF5 reader covering what MED files use.
//!
//! Why our own: the pure-Rust crates available (`hdf5-pure`, `hdf5-reader`)
//! do not read the data-layout message version 2 written by HDF5 1.6, the
//! layout of many older MED files (the seed mesh among them). The subset of
//! HDF5 that MED needs is small and stable: superblocks v0–v3, object
//! headers v1/v2, "old-style" groups (symbol table, v1 B-tree, local heap)
//! and "new-style" groups (link messages, dense links in a fractal heap
//! indexed by a v2 B-tree), data layouts v1–v4 (compact, contiguous,
//! chunked with a v1 B-tree / single chunk / implicit index), the deflate,
//! shuffle and fletcher32 filters, and the integer, float, string and array
//! datatypes. Everything else is reported as unsupported, never guessed.
//!
//! The whole file is read into memory once; contiguous datasets are then
//! borrowed without copying, which keeps reading a million-node mesh fast.

mod checksum;
mod cursor;
mod dataset;
mod dense;
mod group;
mod object;
mod types;
pub mod write;

pub use dataset::Data;
pub use types::{Attribute, Datatype};

use cursor::{Cursor, UNDEF};
use object::ObjectHeader;
use std::fmt;
use std::path::Path;

/// Why an HDF5 file could not be read.
#[derive(Debug, Clone, PartialEq)]
pub enum H5Error {
    /// The file has no HDF5 signature.
    NotHdf5,
    /// A structure runs past the end of the file.
    Truncated { at: u64, needed: u64 },
    /// A structure is malformed.
    Corrupt(String),
    /// A valid HDF5 feature this reader does not implement.
    Unsupported(String),
    /// A path does not exist in the file.
    NotFound(String),
}

impl fmt::Display for H5Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            H5Error::NotHdf5 => write!(f, "not an HDF5 file (no HDF5 signature found)"),
            H5Error::Truncated { at, needed } => write!(
                f,
                "truncated HDF5 file: {needed} bytes needed at byte {at}, past the end of the file"
            ),
            H5Error::Corrupt(m) => write!(f, "corrupt HDF5 file: {m}"),
            H5Error::Unsupported(m) => write!(f, "unsupported HDF5 feature: {m}"),
            H5Error::NotFound(p) => write!(f, "no object `{p}` in the HDF5 file"),
        }
    }
}

impl std::error::Error for H5Error {}

/// An HDF5 file image in memory.
pub struct H5File {
    data: Vec<u8>,
    base: u64,
    offset_size: u8,
    length_size: u8,
    root: u64,
}

/// A group or dataset of the file, by its object header address.
#[derive(Clone)]
pub struct Object {
    header: ObjectHeader,
}

const SIGNATURE: [u8; 8] = [0x89, b'H', b'D', b'F', b'\r', b'\n', 0x1a, b'\n'];

impl H5File {
    pub fn open(path: &Path) -> std::io::Result<Result<H5File, H5Error>> {
        let data = std::fs::read(path)?;
        Ok(H5File::from_bytes(data))
    }

    /// Parse the superblock, searched at 0, 512, 1024, 2048… as the format says.
    pub fn from_bytes(data: Vec<u8>) -> Result<H5File, H5Error> {
        let mut at = 0usize;
        loop {
            if at + 8 > data.len() {
                return Err(H5Error::NotHdf5);
            }
            if data[at..at + 8] == SIGNATURE {
                break;
            }
            at = if at == 0 { 512 } else { at * 2 };
        }
        let mut c = Cursor::new(&data, at + 8, 8, 8);
        let version = c.u8()?;
        let (base, offset_size, length_size, root) = match version {
            0 | 1 => {
                c.skip(4)?; // free-space, root sym table, reserved, shared header versions
                let os = c.u8()?;
                let ls = c.u8()?;
                check_sizes(os, ls)?;
                c.skip(1 + 2 + 2 + 4)?; // reserved, leaf K, internal K, flags
                if version == 1 {
                    c.skip(4)?;
                }
                let mut c = Cursor::new(&data, c.pos, os, ls);
                let base = c.offset()?;
                c.offset()?; // free-space info
                c.offset()?; // end of file
                c.offset()?; // driver info
                c.length()?; // root: link name offset (encoded as a length, as HDF5 does)
                let root = c.offset()?;
                (base, os, ls, root)
            }
            2 | 3 => {
                let os = c.u8()?;
                let ls = c.u8()?;
                check_sizes(os, ls)?;
                c.skip(1)?; // flags
                let mut c = Cursor::new(&data, c.pos, os, ls);
                let base = c.offset()?;
                c.offset()?; // superblock extension
                c.offset()?; // end of file
                let root = c.offset()?;
                (base, os, ls, root)
            }
            v => return Err(H5Error::Unsupported(format!("superblock version {v}"))),
        };
        let base = if base == UNDEF { 0 } else { base };
        Ok(H5File {
            data,
            base,
            offset_size,
            length_size,
            root,
        })
    }

    fn cursor(&self, addr: u64) -> Result<Cursor<'_>, H5Error> {
        let pos = addr
            .checked_add(self.base)
            .filter(|&p| p < self.data.len() as u64)
            .ok_or(H5Error::Truncated {
                at: addr,
                needed: 1,
            })?;
        Ok(Cursor::new(
            &self.data,
            pos as usize,
            self.offset_size,
            self.length_size,
        ))
    }

    /// The bytes `[addr, addr+len)` of the file (addresses relative to the base).
    fn slice(&self, addr: u64, len: u64) -> Result<&[u8], H5Error> {
        let start = addr.checked_add(self.base);
        let end = start.and_then(|s| s.checked_add(len));
        match (start, end) {
            (Some(s), Some(e)) if e <= self.data.len() as u64 => {
                Ok(&self.data[s as usize..e as usize])
            }
            _ => Err(H5Error::Truncated {
                at: addr,
                needed: len,
            }),
        }
    }

    pub fn root(&self) -> Result<Object, H5Error> {
        self.object_at(self.root)
    }

    pub fn object_at(&self, addr: u64) -> Result<Object, H5Error> {
        Ok(Object {
            header: ObjectHeader::read(self, addr)?,
        })
    }

    /// The object at a `/`-separated path from the root, if it exists.
    pub fn get(&self, path: &str) -> Result<Option<Object>, H5Error> {
        let mut obj = self.root()?;
        for part in path.split('/').filter(|p| !p.is_empty()) {
            match self.child(&obj, part)? {
                Some(o) => obj = o,
                None => return Ok(None),
            }
        }
        Ok(Some(obj))
    }

    /// The child of a group by name.
    pub fn child(&self, group: &Object, name: &str) -> Result<Option<Object>, H5Error> {
        for (n, addr) in self.links(group)? {
            if n == name {
                return Ok(Some(self.object_at(addr)?));
            }
        }
        Ok(None)
    }

    /// The (name, object address) of a group's members, in the file's index order.
    pub fn links(&self, group: &Object) -> Result<Vec<(String, u64)>, H5Error> {
        group::links(self, &group.header)
    }

    pub fn attributes(&self, obj: &Object) -> Result<Vec<Attribute>, H5Error> {
        types::attributes(self, &obj.header)
    }

    pub fn attribute(&self, obj: &Object, name: &str) -> Result<Option<Attribute>, H5Error> {
        Ok(self.attributes(obj)?.into_iter().find(|a| a.name == name))
    }

    /// Read a dataset whole.
    pub fn read(&self, obj: &Object) -> Result<Data<'_>, H5Error> {
        dataset::read(self, &obj.header)
    }
}

impl Object {
    pub fn is_dataset(&self) -> bool {
        self.header.find(object::MSG_LAYOUT).is_some()
    }

    pub fn address(&self) -> u64 {
        self.header.addr
    }
}

fn check_sizes(os: u8, ls: u8) -> Result<(), H5Error> {
    if !matches!(os, 2 | 4 | 8) || !matches!(ls, 2 | 4 | 8) {
        return Err(H5Error::Corrupt(format!(
            "superblock offset size {os} / length size {ls}"
        )));
    }
    Ok(())
}
