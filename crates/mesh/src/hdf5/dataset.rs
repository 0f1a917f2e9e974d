//! Dataset reading: data layout messages v1–v4 and the filters MED may use.

use super::cursor::UNDEF;
use super::object::{ObjectHeader, MSG_DATASPACE, MSG_DATATYPE, MSG_FILTERS, MSG_LAYOUT};
use super::types::{decode_float, decode_int, parse_dataspace, trim_name, Datatype};
use super::{Cursor, H5Error, H5File};
use std::borrow::Cow;

/// A dataset's values: its type, shape and raw bytes (borrowed from the
/// file image when stored contiguously).
pub struct Data<'a> {
    pub datatype: Datatype,
    pub dims: Vec<u64>,
    pub raw: Cow<'a, [u8]>,
}

impl Data<'_> {
    pub fn len(&self) -> usize {
        checked_product(&self.dims).unwrap_or(0) as usize
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// All values as `f64` (float or integer datasets).
    pub fn to_f64(&self) -> Result<Vec<f64>, H5Error> {
        match self.datatype {
            Datatype::Float {
                size: 8,
                big_endian: false,
            } => Ok(self
                .raw
                .chunks_exact(8)
                .map(|b| f64::from_le_bytes([b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7]]))
                .collect()),
            Datatype::Float { size, big_endian } => self
                .raw
                .chunks_exact(size.max(1))
                .map(|b| decode_float(b, big_endian).ok_or_else(|| bad_type(&self.datatype)))
                .collect(),
            Datatype::Int { .. } => Ok(self.to_i64()?.into_iter().map(|v| v as f64).collect()),
            _ => Err(bad_type(&self.datatype)),
        }
    }

    /// All values as `i64` (integer datasets of any width and byte order).
    pub fn to_i64(&self) -> Result<Vec<i64>, H5Error> {
        match self.datatype {
            Datatype::Int {
                size: 4,
                signed: true,
                big_endian: false,
            } => Ok(self
                .raw
                .chunks_exact(4)
                .map(|b| i32::from_le_bytes([b[0], b[1], b[2], b[3]]) as i64)
                .collect()),
            Datatype::Int {
                size,
                signed,
                big_endian,
            } => self
                .raw
                .chunks_exact(size.max(1))
                .map(|b| decode_int(b, signed, big_endian).ok_or_else(|| bad_type(&self.datatype)))
                .collect(),
            Datatype::Float { .. } => Ok(self.to_f64()?.into_iter().map(|v| v as i64).collect()),
            _ => Err(bad_type(&self.datatype)),
        }
    }

    /// All values as `i32`, values outside the `i32` range clamped (they
    /// are invalid as node numbers anyway): the fast path for connectivity.
    pub fn to_i32_clamped(&self) -> Result<Vec<i32>, H5Error> {
        match self.datatype {
            Datatype::Int {
                size: 4,
                signed: true,
                big_endian: false,
            } => Ok(self
                .raw
                .chunks_exact(4)
                .map(|b| i32::from_le_bytes([b[0], b[1], b[2], b[3]]))
                .collect()),
            _ => Ok(self
                .to_i64()?
                .into_iter()
                .map(|v| v.clamp(i32::MIN as i64, i32::MAX as i64) as i32)
                .collect()),
        }
    }

    /// Fixed-width names: the bytes cut into `width`-byte pieces, each
    /// trimmed. Works for strings, `i8[width]` arrays and `char` vectors.
    pub fn names(&self, width: usize) -> Vec<String> {
        if width == 0 {
            return Vec::new();
        }
        self.raw.chunks(width).map(trim_name).collect()
    }
}

fn bad_type(dt: &Datatype) -> H5Error {
    H5Error::Unsupported(format!(
        "dataset of type {dt:?} where numbers were expected"
    ))
}

enum Layout {
    Compact(usize, usize),
    Contiguous(u64, u64),
    /// Chunked, indexed by a v1 B-tree.
    ChunkedBtree {
        btree: u64,
        chunk: Vec<u64>,
    },
    /// Chunked, a single chunk (layout v4).
    SingleChunk {
        addr: u64,
        size: Option<u64>,
        chunk: Vec<u64>,
    },
    /// Chunked, chunks stored one after the other unfiltered (layout v4).
    Implicit {
        addr: u64,
        chunk: Vec<u64>,
    },
    /// Chunked, indexed by a fixed array (layout v4, HDF5 ≥ 1.10 `libver=latest`).
    FixedArray {
        header: u64,
        chunk: Vec<u64>,
    },
}

pub fn read<'a>(file: &'a H5File, oh: &ObjectHeader) -> Result<Data<'a>, H5Error> {
    let missing = |what: &str| {
        H5Error::Corrupt(format!(
            "dataset at address {} has no {what} message",
            oh.addr
        ))
    };
    let dt = oh.find(MSG_DATATYPE).ok_or_else(|| missing("datatype"))?;
    let datatype = Datatype::parse(&mut file.msg_cursor(dt)?)?;
    let ds = oh.find(MSG_DATASPACE).ok_or_else(|| missing("dataspace"))?;
    let dims = parse_dataspace(&mut file.msg_cursor(ds)?)?;
    let lm = oh.find(MSG_LAYOUT).ok_or_else(|| missing("layout"))?;
    let layout = parse_layout(&mut file.msg_cursor(lm)?, dims.len())?;
    let filters = match oh.find(MSG_FILTERS) {
        Some(m) => parse_filters(&mut file.msg_cursor(m)?)?,
        None => Vec::new(),
    };
    let esize = datatype.size();
    let total = checked_product(&dims)
        .and_then(|c| c.checked_mul(esize as u64))
        .filter(|&t| t <= MAX_DATASET_BYTES)
        .ok_or_else(|| {
            H5Error::Corrupt(format!("dataset shape {dims:?} is too large to be real"))
        })? as usize;
    let raw: Cow<'a, [u8]> = match layout {
        Layout::Compact(start, len) => {
            if len < total {
                return Err(H5Error::Corrupt(
                    "compact dataset shorter than its shape".into(),
                ));
            }
            Cow::Borrowed(&file.data[start..start + total])
        }
        Layout::Contiguous(addr, _size) => {
            if addr == UNDEF {
                Cow::Owned(vec![0; total])
            } else {
                Cow::Borrowed(file.slice(addr, total as u64)?)
            }
        }
        Layout::ChunkedBtree { btree, chunk } => {
            let mut out = vec![0u8; total];
            if btree != UNDEF {
                chunk_btree(file, btree, &chunk, &dims, esize, &filters, &mut out, 0)?;
            }
            Cow::Owned(out)
        }
        Layout::SingleChunk { addr, size, chunk } => {
            let mut out = vec![0u8; total];
            if addr != UNDEF {
                let bytes = chunk_bytes(&chunk, esize);
                let stored = file.slice(addr, size.unwrap_or(bytes as u64))?;
                let plain = unfilter(stored, &filters, esize)?;
                place_chunk(&plain, &vec![0; dims.len()], &chunk, &dims, esize, &mut out);
            }
            Cow::Owned(out)
        }
        Layout::Implicit { addr, chunk } => {
            let mut out = vec![0u8; total];
            if addr != UNDEF {
                let bytes = chunk_bytes(&chunk, esize) as u64;
                let n = chunk_count(&dims, &chunk, total)?;
                let mut entries = Vec::new();
                for k in 0..n {
                    let at = k
                        .checked_mul(bytes)
                        .and_then(|o| o.checked_add(addr))
                        .ok_or_else(|| H5Error::Corrupt("chunk address overflows".into()))?;
                    entries.push((at, bytes, 0u32));
                }
                place_chunks(file, &entries, &dims, &chunk, esize, &[], &mut out)?;
            }
            Cow::Owned(out)
        }
        Layout::FixedArray { header, chunk } => {
            let mut out = vec![0u8; total];
            if header != UNDEF {
                let n = chunk_count(&dims, &chunk, total)?;
                let bytes = chunk_bytes(&chunk, esize) as u64;
                let entries = fixed_array(file, header, n, bytes, !filters.is_empty())?;
                place_chunks(file, &entries, &dims, &chunk, esize, &filters, &mut out)?;
            }
            Cow::Owned(out)
        }
    };
    Ok(Data {
        datatype,
        dims,
        raw,
    })
}

/// Number of chunks covering the dataset, in row-major chunk order.
fn chunk_count(dims: &[u64], chunk: &[u64], total: usize) -> Result<u64, H5Error> {
    if chunk.len() < dims.len() {
        return Err(H5Error::Corrupt("chunk rank below dataset rank".into()));
    }
    let per: Vec<u64> = dims
        .iter()
        .zip(chunk)
        .map(|(&d, &c)| d.div_ceil(c.max(1)))
        .collect();
    let n = checked_product(&per).unwrap_or(u64::MAX);
    if n > total as u64 {
        return Err(H5Error::Corrupt("more chunks than elements".into()));
    }
    Ok(n)
}

/// Place chunks given as (address, stored size, filter mask) in row-major chunk order.
fn place_chunks(
    file: &H5File,
    entries: &[(u64, u64, u32)],
    dims: &[u64],
    chunk: &[u64],
    esize: usize,
    filters: &[Filter],
    out: &mut [u8],
) -> Result<(), H5Error> {
    let per: Vec<u64> = dims
        .iter()
        .zip(chunk)
        .map(|(&d, &c)| d.div_ceil(c.max(1)))
        .collect();
    for (k, &(addr, size, mask)) in entries.iter().enumerate() {
        if addr == UNDEF {
            continue;
        }
        let mut origin = vec![0u64; dims.len()];
        let mut rest = k as u64;
        for d in (0..dims.len()).rev() {
            origin[d] = (rest % per[d].max(1)) * chunk[d];
            rest /= per[d].max(1);
        }
        let active: Vec<Filter> = filters
            .iter()
            .enumerate()
            .filter(|(i, _)| mask & (1 << i) == 0)
            .map(|(_, f)| Filter { id: f.id })
            .collect();
        let plain = unfilter(file.slice(addr, size)?, &active, esize)?;
        place_chunk(&plain, &origin, chunk, dims, esize, out);
    }
    Ok(())
}

/// The chunk entries of a fixed-array index (`FAHD` header, `FADB` data
/// block, pages when there are more than 2^page_bits entries).
fn fixed_array(
    file: &H5File,
    header: u64,
    n: u64,
    bytes: u64,
    filtered: bool,
) -> Result<Vec<(u64, u64, u32)>, H5Error> {
    let mut c = file.cursor(header)?;
    c.signature(b"FAHD", "fixed array header")?;
    c.skip(2)?; // version, client
    let entry_size = c.u8()? as usize;
    let page_bits = c.u8()? as u32;
    let count = c.length()?;
    let block = c.offset()?;
    if count < n {
        return Err(H5Error::Corrupt(format!(
            "fixed array of {count} chunks for {n}"
        )));
    }
    let os = file.offset_size as usize;
    let size_bytes = entry_size.saturating_sub(os + 4);
    let mut d = file.cursor(block)?;
    d.signature(b"FADB", "fixed array data block")?;
    d.skip(2)?;
    d.offset()?;
    let page = 1u64.checked_shl(page_bits.min(63)).unwrap_or(u64::MAX);
    let paged = count > page;
    let pages = if paged { count.div_ceil(page) } else { 0 };
    if paged {
        d.skip(pages.div_ceil(8) as usize)?; // page initialised bitmap
        d.skip(4)?; // checksum of the block prefix
    }
    let mut entries = Vec::with_capacity(n.min(1 << 20) as usize);
    for k in 0..n {
        if paged && k > 0 && k % page == 0 {
            d.skip(4)?; // checksum ending the previous page
        }
        let addr = d.offset()?;
        if filtered {
            let size = d.uint(size_bytes)?;
            let mask = d.u32()?;
            entries.push((addr, size, mask));
        } else {
            entries.push((addr, bytes, 0));
        }
    }
    Ok(entries)
}

fn chunk_bytes(chunk: &[u64], esize: usize) -> usize {
    (checked_product(chunk).unwrap_or(0) as usize).saturating_mul(esize)
}

/// Larger datasets than this (4 GiB) are taken as corruption, not allocated.
const MAX_DATASET_BYTES: u64 = 1 << 32;

/// The product of dimensions, `None` on overflow.
fn checked_product(dims: &[u64]) -> Option<u64> {
    dims.iter().try_fold(1u64, |acc, &d| acc.checked_mul(d))
}

fn parse_layout(c: &mut Cursor<'_>, rank: usize) -> Result<Layout, H5Error> {
    let version = c.u8()?;
    match version {
        1 | 2 => {
            let dimensionality = c.u8()? as usize;
            let class = c.u8()?;
            c.skip(5)?;
            let addr = if class != 0 { c.offset()? } else { UNDEF };
            let mut sizes = Vec::with_capacity(dimensionality);
            for _ in 0..dimensionality {
                sizes.push(c.u32()? as u64);
            }
            match class {
                0 => {
                    let len = c.u32()? as usize;
                    let start = c.pos;
                    c.skip(len)?;
                    Ok(Layout::Compact(start, len))
                }
                1 => Ok(Layout::Contiguous(addr, 0)),
                2 => {
                    c.u32()?; // element size
                    sizes.truncate(rank);
                    Ok(Layout::ChunkedBtree {
                        btree: addr,
                        chunk: sizes,
                    })
                }
                k => Err(H5Error::Unsupported(format!("layout class {k}"))),
            }
        }
        // Version 5 (HDF5 2.0) encodes the classes read here as version 4 does.
        3..=5 => {
            let class = c.u8()?;
            match class {
                0 => {
                    let len = c.u16()? as usize;
                    let start = c.pos;
                    c.skip(len)?;
                    Ok(Layout::Compact(start, len))
                }
                1 => {
                    let addr = c.offset()?;
                    let size = c.length()?;
                    Ok(Layout::Contiguous(addr, size))
                }
                2 if version == 3 => {
                    let dimensionality = c.u8()? as usize;
                    let btree = c.offset()?;
                    let mut chunk = Vec::with_capacity(dimensionality);
                    for _ in 0..dimensionality {
                        chunk.push(c.u32()? as u64);
                    }
                    chunk.truncate(rank);
                    Ok(Layout::ChunkedBtree { btree, chunk })
                }
                2 => {
                    let flags = c.u8()?;
                    let dimensionality = c.u8()? as usize;
                    let width = c.u8()? as usize;
                    let mut chunk = Vec::with_capacity(dimensionality);
                    for _ in 0..dimensionality {
                        chunk.push(c.uint(width)?);
                    }
                    chunk.truncate(rank);
                    let index = c.u8()?;
                    match index {
                        1 => {
                            let size = if flags & 2 != 0 {
                                let s = c.length()?;
                                c.u32()?;
                                Some(s)
                            } else {
                                None
                            };
                            let addr = c.offset()?;
                            Ok(Layout::SingleChunk { addr, size, chunk })
                        }
                        2 => Ok(Layout::Implicit {
                            addr: c.offset()?,
                            chunk,
                        }),
                        3 => {
                            c.u8()?; // page bits, repeated in the array header
                            Ok(Layout::FixedArray {
                                header: c.offset()?,
                                chunk,
                            })
                        }
                        k => Err(H5Error::Unsupported(format!(
                            "chunk index type {k} (extensible array or v2 B-tree)"
                        ))),
                    }
                }
                k => Err(H5Error::Unsupported(format!("layout class {k}"))),
            }
        }
        v => Err(H5Error::Unsupported(format!(
            "data layout message version {v}"
        ))),
    }
}

#[derive(Debug)]
struct Filter {
    id: u16,
}

fn parse_filters(c: &mut Cursor<'_>) -> Result<Vec<Filter>, H5Error> {
    let version = c.u8()?;
    let n = c.u8()? as usize;
    if version == 1 {
        c.skip(6)?;
    }
    let mut out = Vec::with_capacity(n);
    for _ in 0..n {
        let id = c.u16()?;
        let name_len = if version == 1 || id >= 256 {
            c.u16()? as usize
        } else {
            0
        };
        c.u16()?; // flags
        let nvalues = c.u16()? as usize;
        if version == 1 {
            c.skip(name_len.div_ceil(8) * 8)?;
        } else {
            c.skip(name_len)?;
        }
        c.skip(4 * nvalues)?;
        if version == 1 && nvalues % 2 == 1 {
            c.skip(4)?;
        }
        out.push(Filter { id });
    }
    Ok(out)
}

/// Undo the filter pipeline on one stored chunk (filters apply in reverse).
fn unfilter<'a>(
    data: &'a [u8],
    filters: &[Filter],
    esize: usize,
) -> Result<Cow<'a, [u8]>, H5Error> {
    let mut buf: Cow<'a, [u8]> = Cow::Borrowed(data);
    for f in filters.iter().rev() {
        buf = match f.id {
            1 => Cow::Owned(
                miniz_oxide::inflate::decompress_to_vec_zlib(&buf)
                    .map_err(|e| H5Error::Corrupt(format!("deflate: {e:?}")))?,
            ),
            2 => Cow::Owned(unshuffle(&buf, esize)),
            3 => {
                let n = buf.len().saturating_sub(4);
                Cow::Owned(buf[..n].to_vec())
            }
            id => {
                return Err(H5Error::Unsupported(format!(
                    "filter {id} (only deflate, shuffle and fletcher32 are read)"
                )))
            }
        };
    }
    Ok(buf)
}

fn unshuffle(data: &[u8], esize: usize) -> Vec<u8> {
    if esize <= 1 {
        return data.to_vec();
    }
    let n = data.len() / esize;
    let mut out = data.to_vec();
    for b in 0..esize {
        for i in 0..n {
            out[i * esize + b] = data[b * n + i];
        }
    }
    out
}

/// Copy a chunk whose first element is at `origin` into the row-major output.
fn place_chunk(
    data: &[u8],
    origin: &[u64],
    chunk: &[u64],
    dims: &[u64],
    esize: usize,
    out: &mut [u8],
) {
    let rank = dims.len();
    if rank == 0 {
        let n = esize.min(data.len()).min(out.len());
        out[..n].copy_from_slice(&data[..n]);
        return;
    }
    if chunk.len() < rank || chunk.contains(&0) {
        return;
    }
    let Some(rows) = checked_product(&chunk[..rank - 1]) else {
        return;
    };
    let last = chunk[rank - 1];
    for r in 0..rows {
        // Global coordinates of the row's first element.
        let mut rest = r;
        let mut global = vec![0u64; rank];
        let mut inside = true;
        for d in (0..rank - 1).rev() {
            global[d] = origin[d].saturating_add(rest % chunk[d]);
            rest /= chunk[d];
            inside &= global[d] < dims[d];
        }
        global[rank - 1] = origin[rank - 1];
        if !inside || global[rank - 1] >= dims[rank - 1] {
            continue;
        }
        let len = last.min(dims[rank - 1] - origin[rank - 1]) as usize;
        let mut flat = 0u64;
        for d in 0..rank {
            flat = flat * dims[d] + global[d];
        }
        let Some(src) = r
            .checked_mul(last)
            .and_then(|e| (e as usize).checked_mul(esize))
        else {
            return;
        };
        let dst = flat as usize * esize;
        let n = len * esize;
        if src + n <= data.len() && dst + n <= out.len() {
            out[dst..dst + n].copy_from_slice(&data[src..src + n]);
        }
    }
}

#[allow(clippy::too_many_arguments)]
fn chunk_btree(
    file: &H5File,
    addr: u64,
    chunk: &[u64],
    dims: &[u64],
    esize: usize,
    filters: &[Filter],
    out: &mut [u8],
    depth: usize,
) -> Result<(), H5Error> {
    if depth > 64 {
        return Err(H5Error::Corrupt(
            "chunk B-tree deeper than 64 levels".into(),
        ));
    }
    let rank = dims.len();
    let mut c = file.cursor(addr)?;
    c.signature(b"TREE", "v1 B-tree")?;
    let node_type = c.u8()?;
    if node_type != 1 {
        return Err(H5Error::Corrupt(format!(
            "chunk B-tree node of type {node_type}"
        )));
    }
    let level = c.u8()?;
    let entries = c.u16()? as usize;
    c.offset()?;
    c.offset()?;
    for _ in 0..entries {
        let size = c.u32()? as u64;
        let mask = c.u32()?;
        let mut origin = Vec::with_capacity(rank);
        for _ in 0..rank {
            origin.push(c.u64()?);
        }
        c.u64()?; // element-size dimension, always 0
        let child = c.offset()?;
        if level > 0 {
            chunk_btree(file, child, chunk, dims, esize, filters, out, depth + 1)?;
        } else {
            let stored = file.slice(child, size)?;
            // A set bit in the mask means that filter was skipped for this chunk.
            let active: Vec<Filter> = filters
                .iter()
                .enumerate()
                .filter(|(i, _)| mask & (1 << i) == 0)
                .map(|(_, f)| Filter { id: f.id })
                .collect();
            let plain = unfilter(stored, &active, esize)?;
            place_chunk(&plain, &origin, chunk, dims, esize, out);
        }
    }
    Ok(())
}
