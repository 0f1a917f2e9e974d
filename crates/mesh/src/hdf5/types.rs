//! Datatypes, dataspaces and attributes.

use super::object::{ObjectHeader, MSG_ATTRIBUTE, MSG_ATTRIBUTE_INFO};
use super::{Cursor, H5Error, H5File};

/// The datatypes MED files use.
#[derive(Clone, Debug, PartialEq)]
pub enum Datatype {
    Int {
        size: usize,
        signed: bool,
        big_endian: bool,
    },
    Float {
        size: usize,
        big_endian: bool,
    },
    /// Fixed-length string of `size` bytes.
    String {
        size: usize,
    },
    /// Fixed-size array of a base type (MED 3+ stores 80-character names as `i8[80]`).
    Array {
        dims: Vec<u32>,
        base: Box<Datatype>,
    },
    /// Any other class (compound, opaque…): only its size is known.
    Other {
        class: u8,
        size: usize,
    },
}

impl Datatype {
    pub fn size(&self) -> usize {
        match self {
            Datatype::Int { size, .. }
            | Datatype::Float { size, .. }
            | Datatype::String { size }
            | Datatype::Other { size, .. } => *size,
            Datatype::Array { dims, base } => dims
                .iter()
                .try_fold(base.size(), |acc, &d| acc.checked_mul(d as usize))
                .unwrap_or(usize::MAX),
        }
    }

    pub(super) fn parse(c: &mut Cursor<'_>) -> Result<Datatype, H5Error> {
        let cv = c.u8()?;
        let class = cv & 0x0f;
        let version = cv >> 4;
        let bits = c.bytes(3)?;
        let size = c.u32()? as usize;
        Ok(match class {
            0 => {
                c.skip(4)?; // bit offset, precision
                Datatype::Int {
                    size,
                    signed: bits[0] & 0x08 != 0,
                    big_endian: bits[0] & 0x01 != 0,
                }
            }
            1 => {
                c.skip(12)?;
                if bits[0] & 0x40 != 0 {
                    return Err(H5Error::Unsupported("VAX-order floats".into()));
                }
                Datatype::Float {
                    size,
                    big_endian: bits[0] & 0x01 != 0,
                }
            }
            3 => Datatype::String { size },
            10 => {
                let rank = c.u8()? as usize;
                if version < 3 {
                    c.skip(3)?;
                }
                let mut dims = Vec::with_capacity(rank);
                for _ in 0..rank {
                    dims.push(c.u32()?);
                }
                if version < 3 {
                    c.skip(4 * rank)?; // permutation indices
                }
                let base = Datatype::parse(c)?;
                if matches!(base, Datatype::Array { .. }) {
                    return Err(H5Error::Unsupported("array of arrays".into()));
                }
                let base = Box::new(base);
                Datatype::Array { dims, base }
            }
            other => Datatype::Other { class: other, size },
        })
    }
}

/// The shape of a dataset or attribute: `None` for a null dataspace.
pub(super) fn parse_dataspace(c: &mut Cursor<'_>) -> Result<Vec<u64>, H5Error> {
    let version = c.u8()?;
    let rank = c.u8()? as usize;
    let _flags = c.u8()?;
    match version {
        1 => c.skip(5)?,
        2 => {
            let kind = c.u8()?;
            if kind == 2 {
                return Ok(vec![0]);
            }
        }
        v => return Err(H5Error::Unsupported(format!("dataspace version {v}"))),
    }
    let mut dims = Vec::with_capacity(rank);
    for _ in 0..rank {
        dims.push(c.length()?);
    }
    Ok(dims)
}

/// An attribute, with its raw value bytes.
#[derive(Clone, Debug)]
pub struct Attribute {
    pub name: String,
    pub datatype: Datatype,
    pub dims: Vec<u64>,
    pub raw: Vec<u8>,
}

impl Attribute {
    /// The value as an integer, when it is a scalar (or first element) of an integer type.
    pub fn as_i64(&self) -> Option<i64> {
        match &self.datatype {
            Datatype::Int {
                size,
                signed,
                big_endian,
            } => decode_int(self.raw.get(..*size)?, *signed, *big_endian),
            Datatype::Float { .. } => self.as_f64().map(|v| v as i64),
            _ => None,
        }
    }

    pub fn as_f64(&self) -> Option<f64> {
        match &self.datatype {
            Datatype::Float { size, big_endian } => {
                decode_float(self.raw.get(..*size)?, *big_endian)
            }
            Datatype::Int { .. } => self.as_i64().map(|v| v as f64),
            _ => None,
        }
    }

    /// The value as text, trailing NULs and spaces removed.
    pub fn as_string(&self) -> Option<String> {
        match &self.datatype {
            Datatype::String { .. } => Some(trim_name(&self.raw)),
            _ => None,
        }
    }
}

/// Decode a fixed-width name: up to the first NUL, trailing blanks removed.
pub fn trim_name(raw: &[u8]) -> String {
    let end = raw.iter().position(|&b| b == 0).unwrap_or(raw.len());
    String::from_utf8_lossy(&raw[..end]).trim_end().to_string()
}

pub fn decode_int(b: &[u8], signed: bool, big_endian: bool) -> Option<i64> {
    let n = b.len();
    if n == 0 || n > 8 {
        return None;
    }
    let mut v: u64 = 0;
    if big_endian {
        for &x in b {
            v = (v << 8) | x as u64;
        }
    } else {
        for &x in b.iter().rev() {
            v = (v << 8) | x as u64;
        }
    }
    if signed && n < 8 && v & (1 << (8 * n - 1)) != 0 {
        v |= !0u64 << (8 * n);
    }
    Some(v as i64)
}

pub fn decode_float(b: &[u8], big_endian: bool) -> Option<f64> {
    match b.len() {
        8 => {
            let a: [u8; 8] = b.try_into().ok()?;
            Some(if big_endian {
                f64::from_be_bytes(a)
            } else {
                f64::from_le_bytes(a)
            })
        }
        4 => {
            let a: [u8; 4] = b.try_into().ok()?;
            Some(if big_endian {
                f32::from_be_bytes(a)
            } else {
                f32::from_le_bytes(a)
            } as f64)
        }
        _ => None,
    }
}

pub(super) fn attributes(file: &H5File, oh: &ObjectHeader) -> Result<Vec<Attribute>, H5Error> {
    let mut out = Vec::new();
    for m in oh.all(MSG_ATTRIBUTE) {
        out.push(attribute_message(&mut file.msg_cursor(m)?)?);
    }

    if let Some(m) = oh.find(MSG_ATTRIBUTE_INFO) {
        // Dense storage (more than 8 attributes, as on MED 3+ mesh groups):
        // attribute messages kept in a fractal heap.
        let mut c = file.msg_cursor(m)?;
        c.skip(1)?;
        let flags = c.u8()?;
        if flags & 1 != 0 {
            c.skip(2)?;
        }
        let heap = c.offset()?;
        if heap != super::cursor::UNDEF {
            let mut dense = Vec::new();
            super::dense::walk_heap(file, heap, &mut |region| {
                let mut c = Cursor::new(region, 0, file.offset_size, file.length_size);
                while c.pos < region.len() {
                    let mut peek = c.clone();
                    if !matches!(peek.u8()?, 1..=3) {
                        break;
                    }
                    match attribute_message(&mut c) {
                        Ok(a) => dense.push(a),
                        Err(_) => break,
                    }
                }
                Ok(())
            })?;
            dense.sort_by(|a, b| a.name.cmp(&b.name));
            out.extend(dense);
        }
    }
    Ok(out)
}

/// One attribute message (versions 1–3; version 1 pads its parts to 8 bytes).
fn attribute_message(c: &mut Cursor<'_>) -> Result<Attribute, H5Error> {
    let version = c.u8()?;
    let flags = c.u8()?;
    if flags & 0x03 != 0 {
        return Err(H5Error::Unsupported(
            "attribute with a shared datatype".into(),
        ));
    }
    let name_len = c.u16()? as usize;
    let dt_len = c.u16()? as usize;
    let ds_len = c.u16()? as usize;
    if version == 3 {
        c.skip(1)?;
    }
    let pad = |n: usize| if version == 1 { n.div_ceil(8) * 8 } else { n };
    let name = trim_name(c.bytes(pad(name_len))?);
    let dt_start = c.pos;
    let datatype = Datatype::parse(&mut c.clone())?;
    c.pos = dt_start;
    c.skip(pad(dt_len))?;
    let ds_start = c.pos;
    let dims = parse_dataspace(&mut c.clone())?;
    c.pos = ds_start;
    c.skip(pad(ds_len))?;
    let count = dims
        .iter()
        .try_fold(1u64, |acc, &d| acc.checked_mul(d))
        .unwrap_or(u64::MAX);
    let size = (count.min(usize::MAX as u64) as usize).saturating_mul(datatype.size());
    let raw = c.bytes(size)?.to_vec();
    Ok(Attribute {
        name,
        datatype,
        dims,
        raw,
    })
}
