//! Bounds-checked little-endian reading of the file image.

use super::H5Error;

/// The "undefined address" of HDF5: all bits set.
pub const UNDEF: u64 = u64::MAX;

/// A read position in the file image. Every read checks bounds, so a
/// truncated or corrupt file gives an error instead of a panic.
#[derive(Clone)]
pub struct Cursor<'a> {
    data: &'a [u8],
    pub pos: usize,
    offset_size: u8,
    length_size: u8,
}

impl<'a> Cursor<'a> {
    pub fn new(data: &'a [u8], pos: usize, offset_size: u8, length_size: u8) -> Self {
        Cursor {
            data,
            pos,
            offset_size,
            length_size,
        }
    }

    pub fn bytes(&mut self, n: usize) -> Result<&'a [u8], H5Error> {
        let end = self.pos.checked_add(n).filter(|&e| e <= self.data.len());
        match end {
            Some(end) => {
                let s = &self.data[self.pos..end];
                self.pos = end;
                Ok(s)
            }
            None => Err(H5Error::Truncated {
                at: self.pos as u64,
                needed: n as u64,
            }),
        }
    }

    pub fn skip(&mut self, n: usize) -> Result<(), H5Error> {
        self.bytes(n).map(|_| ())
    }

    pub fn u8(&mut self) -> Result<u8, H5Error> {
        Ok(self.bytes(1)?[0])
    }

    pub fn u16(&mut self) -> Result<u16, H5Error> {
        Ok(self.uint(2)? as u16)
    }

    pub fn u32(&mut self) -> Result<u32, H5Error> {
        Ok(self.uint(4)? as u32)
    }

    pub fn u64(&mut self) -> Result<u64, H5Error> {
        self.uint(8)
    }

    /// A little-endian unsigned integer of `n` (≤ 8) bytes.
    pub fn uint(&mut self, n: usize) -> Result<u64, H5Error> {
        if n > 8 {
            return Err(H5Error::Corrupt(format!("integer field of {n} bytes")));
        }
        let b = self.bytes(n)?;
        Ok(b.iter().rev().fold(0u64, |acc, &x| (acc << 8) | x as u64))
    }

    /// A file address; all bits set means "undefined" and is returned as [`UNDEF`].
    pub fn offset(&mut self) -> Result<u64, H5Error> {
        let n = self.offset_size as usize;
        let v = self.uint(n)?;
        if n < 8 && v == (1u64 << (8 * n)) - 1 {
            Ok(UNDEF)
        } else {
            Ok(v)
        }
    }

    pub fn length(&mut self) -> Result<u64, H5Error> {
        self.uint(self.length_size as usize)
    }

    /// Expect a 4-byte signature such as `b"TREE"`.
    pub fn signature(&mut self, sig: &[u8; 4], what: &str) -> Result<(), H5Error> {
        let at = self.pos;
        if self.bytes(4)? != sig {
            return Err(H5Error::Corrupt(format!(
                "expected {what} signature {:?} at byte {at}",
                String::from_utf8_lossy(sig)
            )));
        }
        Ok(())
    }
}
