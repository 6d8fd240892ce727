//! A bounds-checked big-endian reader, so that no parser in the codec ever indexes a
//! slice directly (and so can never panic on hostile input).

/// Reads network-order fields from a byte slice. Every read is checked; running out
/// of bytes yields `None` and leaves the reader where it was.
#[derive(Debug, Clone)]
pub(crate) struct Reader<'a> {
    buf: &'a [u8],
}

impl<'a> Reader<'a> {
    pub(crate) fn new(buf: &'a [u8]) -> Self {
        Self { buf }
    }

    pub(crate) fn take(&mut self, n: usize) -> Option<&'a [u8]> {
        let (head, tail) = self.buf.split_at_checked(n)?;
        self.buf = tail;
        Some(head)
    }

    pub(crate) fn array<const N: usize>(&mut self) -> Option<[u8; N]> {
        self.take(N)?.try_into().ok()
    }

    pub(crate) fn u8(&mut self) -> Option<u8> {
        self.array::<1>().map(|[b]| b)
    }

    pub(crate) fn u16(&mut self) -> Option<u16> {
        self.array().map(u16::from_be_bytes)
    }

    pub(crate) fn i16(&mut self) -> Option<i16> {
        self.array().map(i16::from_be_bytes)
    }

    pub(crate) fn u32(&mut self) -> Option<u32> {
        self.array().map(u32::from_be_bytes)
    }

    pub(crate) fn i32(&mut self) -> Option<i32> {
        self.array().map(i32::from_be_bytes)
    }

    /// Everything not yet read.
    pub(crate) fn rest(&mut self) -> &'a [u8] {
        std::mem::take(&mut self.buf)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_big_endian_and_stops_cleanly_at_the_end() {
        let mut r = Reader::new(&[0x12, 0x34, 0xFF, 0xFE, 0x01]);
        assert_eq!(r.u16(), Some(0x1234));
        assert_eq!(r.i16(), Some(-2));
        assert_eq!(r.u16(), None, "one byte left is not a u16");
        assert_eq!(r.u8(), Some(1), "a failed read must not consume");
        assert_eq!(r.u8(), None);
    }
}
