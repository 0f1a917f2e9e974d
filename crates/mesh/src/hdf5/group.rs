//! Group membership: old-style symbol tables (v1 B-tree of symbol nodes,
//! names in a local heap) and new-style link messages.

use super::cursor::UNDEF;
use super::object::{ObjectHeader, MSG_LINK, MSG_LINK_INFO, MSG_SYMBOL_TABLE};
use super::{H5Error, H5File};

pub fn links(file: &H5File, oh: &ObjectHeader) -> Result<Vec<(String, u64)>, H5Error> {
    if let Some(m) = oh.find(MSG_SYMBOL_TABLE) {
        let mut c = file.msg_cursor(m)?;
        let btree = c.offset()?;
        let heap = c.offset()?;
        let names = local_heap(file, heap)?;
        let mut out = Vec::new();
        symbol_btree(file, btree, names, &mut out, 0)?;
        return Ok(out);
    }
    let mut out = Vec::new();
    for m in oh.all(MSG_LINK) {
        if let Some(link) = link_message(file, &mut file.msg_cursor(m)?)? {
            out.push(link);
        }
    }
    if let Some(m) = oh.find(MSG_LINK_INFO) {
        let mut c = file.msg_cursor(m)?;
        c.skip(1)?;
        let flags = c.u8()?;
        if flags & 1 != 0 {
            c.skip(8)?;
        }
        let heap = c.offset()?;
        if heap != UNDEF {
            super::dense::dense_links(file, heap, &mut out)?;
        }
    }
    Ok(out)
}

/// The data segment of a local heap (`HEAP`), where symbol names live.
fn local_heap(file: &H5File, addr: u64) -> Result<&[u8], H5Error> {
    let mut c = file.cursor(addr)?;
    c.signature(b"HEAP", "local heap")?;
    c.skip(4)?;
    let size = c.length()?;
    c.length()?; // free list
    let data = c.offset()?;
    file.slice(data, size)
}

fn heap_name(heap: &[u8], off: u64) -> Result<String, H5Error> {
    let s = heap
        .get(off as usize..)
        .ok_or_else(|| H5Error::Corrupt(format!("name offset {off} outside the local heap")))?;
    let end = s.iter().position(|&b| b == 0).unwrap_or(s.len());
    Ok(String::from_utf8_lossy(&s[..end]).into_owned())
}

fn symbol_btree(
    file: &H5File,
    addr: u64,
    heap: &[u8],
    out: &mut Vec<(String, u64)>,
    depth: usize,
) -> Result<(), H5Error> {
    if depth > 64 {
        return Err(H5Error::Corrupt(
            "group B-tree deeper than 64 levels".into(),
        ));
    }
    let mut c = file.cursor(addr)?;
    c.signature(b"TREE", "v1 B-tree")?;
    let node_type = c.u8()?;
    if node_type != 0 {
        return Err(H5Error::Corrupt(format!(
            "group B-tree node of type {node_type}"
        )));
    }
    let level = c.u8()?;
    let entries = c.u16()? as usize;
    c.offset()?;
    c.offset()?;
    let mut children = Vec::with_capacity(entries);
    for _ in 0..entries {
        c.length()?; // key: heap offset of the largest name in the child
        children.push(c.offset()?);
    }
    for child in children {
        if level > 0 {
            symbol_btree(file, child, heap, out, depth + 1)?;
        } else {
            symbol_node(file, child, heap, out)?;
        }
    }
    Ok(())
}

fn symbol_node(
    file: &H5File,
    addr: u64,
    heap: &[u8],
    out: &mut Vec<(String, u64)>,
) -> Result<(), H5Error> {
    let mut c = file.cursor(addr)?;
    c.signature(b"SNOD", "symbol table node")?;
    c.skip(2)?;
    let n = c.u16()?;
    for _ in 0..n {
        let name = c.length()?; // heap offset, encoded as a length
        let obj = c.offset()?;
        c.skip(4 + 4 + 16)?; // cache type, reserved, scratch pad
        out.push((heap_name(heap, name)?, obj));
    }
    Ok(())
}

/// Decode a link message; `None` for soft and external links, which MED does not use.
pub fn link_message(
    _file: &H5File,
    c: &mut super::Cursor<'_>,
) -> Result<Option<(String, u64)>, H5Error> {
    let version = c.u8()?;
    if version != 1 {
        return Err(H5Error::Unsupported(format!(
            "link message version {version}"
        )));
    }
    let flags = c.u8()?;
    let kind = if flags & 0x08 != 0 { c.u8()? } else { 0 };
    if flags & 0x04 != 0 {
        c.skip(8)?;
    }
    if flags & 0x10 != 0 {
        c.skip(1)?;
    }
    let len = c.uint(1 << (flags & 3))? as usize;
    let name = String::from_utf8_lossy(c.bytes(len)?).into_owned();
    if kind != 0 {
        return Ok(None);
    }
    Ok(Some((name, c.offset()?)))
}
