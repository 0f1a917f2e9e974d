//! Dense link storage: link messages kept as objects of a fractal heap.
//!
//! Rather than following the v2 B-tree name index, we walk the heap's
//! direct blocks and decode the link messages they hold one after the
//! other: HDF5 allocates heap objects back to back from the start of each
//! block, and a zero version byte marks the free space that ends a block.
//! Links come back sorted by name, HDF5's own iteration order.

use super::cursor::UNDEF;
use super::{H5Error, H5File};

struct Heap {
    width: usize,
    start_block: u64,
    max_direct: u64,
    offset_bytes: usize,
    checksummed: bool,
    filtered: bool,
}

/// Links in dense storage, sorted by name.
pub fn dense_links(
    file: &H5File,
    heap_addr: u64,
    out: &mut Vec<(String, u64)>,
) -> Result<(), H5Error> {
    let mut found = Vec::new();
    walk_heap(file, heap_addr, &mut |region| {
        let mut c = super::Cursor::new(region, 0, file.offset_size, file.length_size);
        while c.pos < region.len() {
            let mut peek = c.clone();
            if peek.u8()? != 1 {
                break;
            }
            match super::group::link_message(file, &mut c) {
                Ok(Some(link)) => found.push(link),
                Ok(None) => {}
                Err(_) => break,
            }
        }
        Ok(())
    })?;
    found.sort_by(|a, b| a.0.cmp(&b.0));
    out.extend(found);
    Ok(())
}

/// Call `visit` with the object region of every direct block of a fractal heap.
pub fn walk_heap(
    file: &H5File,
    heap_addr: u64,
    visit: &mut dyn FnMut(&[u8]) -> Result<(), H5Error>,
) -> Result<(), H5Error> {
    let mut c = file.cursor(heap_addr)?;
    c.signature(b"FRHP", "fractal heap")?;
    c.skip(1)?; // version
    c.u16()?; // heap ID length
    let filter_len = c.u16()?;
    let flags = c.u8()?;
    c.u32()?; // max managed object size
    c.length()?; // next huge ID
    c.offset()?; // huge objects B-tree
    c.length()?; // free space
    c.offset()?; // free-space manager
    c.length()?; // managed space
    c.length()?; // allocated managed space
    c.length()?; // direct block allocation iterator
    c.length()?; // managed objects
    c.length()?; // huge size
    c.length()?; // huge count
    c.length()?; // tiny size
    c.length()?; // tiny count
    let width = c.u16()? as usize;
    let start_block = c.length()?;
    let max_direct = c.length()?;
    let max_heap_bits = c.u16()? as usize;
    c.u16()?; // starting rows
    let root = c.offset()?;
    let rows = c.u16()? as usize;
    let heap = Heap {
        width,
        start_block,
        max_direct,
        offset_bytes: max_heap_bits.div_ceil(8),
        checksummed: flags & 2 != 0,
        filtered: filter_len > 0,
    };
    if heap.filtered {
        return Err(H5Error::Unsupported(
            "filtered fractal heap for dense links".into(),
        ));
    }
    if width == 0 || start_block == 0 {
        return Err(H5Error::Corrupt(
            "fractal heap with empty doubling table".into(),
        ));
    }
    if root != UNDEF {
        if rows == 0 {
            direct_block(file, &heap, root, start_block, visit)?;
        } else {
            indirect_block(file, &heap, root, rows, visit, 0)?;
        }
    }
    Ok(())
}

fn block_size(heap: &Heap, row: usize) -> u64 {
    if row == 0 {
        heap.start_block
    } else {
        heap.start_block.saturating_mul(1u64 << (row - 1).min(62))
    }
}

fn indirect_block(
    file: &H5File,
    heap: &Heap,
    addr: u64,
    rows: usize,
    visit: &mut dyn FnMut(&[u8]) -> Result<(), H5Error>,
    depth: usize,
) -> Result<(), H5Error> {
    if depth > 16 {
        return Err(H5Error::Corrupt("fractal heap nested too deep".into()));
    }
    let mut c = file.cursor(addr)?;
    c.signature(b"FHIB", "fractal heap indirect block")?;
    c.skip(1)?;
    c.offset()?;
    c.skip(heap.offset_bytes)?;
    let mut children = Vec::new();
    for row in 0..rows {
        let size = block_size(heap, row);
        for _ in 0..heap.width {
            let child = c.offset()?;
            children.push((child, size));
        }
    }
    for (child, size) in children {
        if child == UNDEF {
            continue;
        }
        if size <= heap.max_direct {
            direct_block(file, heap, child, size, visit)?;
        } else {
            // Rows of a child indirect block: enough to span its size.
            let first = heap.start_block.saturating_mul(heap.width as u64);
            let mut nrows = 1usize;
            let mut span = first;
            while span < size && nrows < 64 {
                span = span.saturating_mul(2);
                nrows += 1;
            }
            indirect_block(file, heap, child, nrows, visit, depth + 1)?;
        }
    }
    Ok(())
}

fn direct_block(
    file: &H5File,
    heap: &Heap,
    addr: u64,
    size: u64,
    visit: &mut dyn FnMut(&[u8]) -> Result<(), H5Error>,
) -> Result<(), H5Error> {
    let block = file.slice(addr, size)?;
    if block.get(..4) != Some(b"FHDB") {
        return Err(H5Error::Corrupt(format!(
            "expected fractal heap direct block at byte {addr}"
        )));
    }
    // The checksum of a direct block is part of its header, before the objects.
    let header = 4
        + 1
        + file.offset_size as usize
        + heap.offset_bytes
        + if heap.checksummed { 4 } else { 0 };
    visit(block.get(header..).unwrap_or(&[]))
}
