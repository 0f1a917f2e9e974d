//! Object headers (versions 1 and 2) and their messages.

use super::{H5Error, H5File};

pub const MSG_DATASPACE: u16 = 0x01;
pub const MSG_LINK_INFO: u16 = 0x02;
pub const MSG_DATATYPE: u16 = 0x03;
pub const MSG_LINK: u16 = 0x06;
pub const MSG_LAYOUT: u16 = 0x08;
pub const MSG_FILTERS: u16 = 0x0B;
pub const MSG_ATTRIBUTE: u16 = 0x0C;
pub const MSG_CONTINUATION: u16 = 0x10;
pub const MSG_SYMBOL_TABLE: u16 = 0x11;
pub const MSG_ATTRIBUTE_INFO: u16 = 0x15;

/// One header message: its type and where its body lies in the file image.
#[derive(Clone, Debug)]
pub struct Message {
    pub ty: u16,
    pub flags: u8,
    /// Absolute position of the body in the file image.
    pub start: usize,
    pub len: usize,
}

#[derive(Clone, Debug)]
pub struct ObjectHeader {
    pub addr: u64,
    pub messages: Vec<Message>,
}

impl ObjectHeader {
    pub fn read(file: &H5File, addr: u64) -> Result<ObjectHeader, H5Error> {
        let mut c = file.cursor(addr)?;
        let start = c.pos;
        let mut messages = Vec::new();
        // Blocks of messages still to scan: (start, end, version-2 layout?)
        let mut blocks: Vec<(usize, usize)> = Vec::new();
        let v2 = c.bytes(4)? == b"OHDR";
        let mut flags = 0u8;
        if v2 {
            let version = c.u8()?;
            if version != 2 {
                return Err(H5Error::Unsupported(format!(
                    "object header version {version}"
                )));
            }
            flags = c.u8()?;
            if flags & 0x20 != 0 {
                c.skip(16)?;
            }
            if flags & 0x10 != 0 {
                c.skip(4)?;
            }
            let size = c.uint(1 << (flags & 3))? as usize;
            blocks.push((c.pos, c.pos.saturating_add(size)));
        } else {
            c.pos = start;
            let version = c.u8()?;
            if version != 1 {
                return Err(H5Error::Corrupt(format!(
                    "no object header at address {addr} (version byte {version})"
                )));
            }
            c.skip(1)?;
            let _count = c.u16()?;
            c.skip(4)?; // reference count
            let size = c.u32()? as usize;
            c.skip(4)?; // alignment padding of the v1 prefix
            blocks.push((c.pos, c.pos.saturating_add(size)));
        }
        let mut i = 0;
        // A corrupt file could chain continuations forever: bound the count.
        while i < blocks.len() && i < 10_000 {
            let (bstart, bend) = blocks[i];
            i += 1;
            let mut c = super::Cursor::new(&file.data, bstart, file.offset_size, file.length_size);
            let bend = bend.min(file.data.len());
            let header_len = if v2 {
                4 + if flags & 0x04 != 0 { 2 } else { 0 }
            } else {
                8
            };
            while c.pos + header_len <= bend {
                let (ty, size, mflags) = if v2 {
                    let ty = c.u8()? as u16;
                    let size = c.u16()? as usize;
                    let f = c.u8()?;
                    if flags & 0x04 != 0 {
                        c.skip(2)?;
                    }
                    (ty, size, f)
                } else {
                    let ty = c.u16()?;
                    let size = c.u16()? as usize;
                    let f = c.u8()?;
                    c.skip(3)?;
                    (ty, size, f)
                };
                let body = c.pos;
                if body + size > bend {
                    return Err(H5Error::Corrupt(format!(
                        "header message of type {ty} overruns its block in object {addr}"
                    )));
                }
                c.skip(size)?;
                if ty == MSG_CONTINUATION {
                    let mut m =
                        super::Cursor::new(&file.data, body, file.offset_size, file.length_size);
                    let off = m.offset()?;
                    let len = m.length()? as usize;
                    let mut cc = file.cursor(off)?;
                    let s = cc.pos;
                    if v2 {
                        cc.signature(b"OCHK", "object header continuation")?;
                        blocks.push((s + 4, (s + len).saturating_sub(4)));
                    } else {
                        blocks.push((s, s + len));
                    }
                } else if ty != 0 {
                    messages.push(Message {
                        ty,
                        flags: mflags,
                        start: body,
                        len: size,
                    });
                }
            }
        }
        Ok(ObjectHeader { addr, messages })
    }

    pub fn find(&self, ty: u16) -> Option<&Message> {
        self.messages.iter().find(|m| m.ty == ty)
    }

    pub fn all(&self, ty: u16) -> impl Iterator<Item = &Message> {
        self.messages.iter().filter(move |m| m.ty == ty)
    }
}

impl H5File {
    /// A cursor on a message body.
    pub(super) fn msg_cursor(&self, m: &Message) -> Result<super::Cursor<'_>, H5Error> {
        if m.flags & 0x02 != 0 {
            return Err(H5Error::Unsupported(format!(
                "shared header message of type {}",
                m.ty
            )));
        }
        Ok(super::Cursor::new(
            &self.data[..m.start + m.len],
            m.start,
            self.offset_size,
            self.length_size,
        ))
    }
}
