//! The PLY body as a stream of numbers, from ASCII text or binary of either endianness.

use super::header::{Scalar, type_name};

/// Why a value could not be read.
pub(super) enum ReadError {
    /// The data ended.
    End,
    /// An ASCII token that is not a number of the property's type.
    Bad(String),
}

/// The body: a stream of numbers, ASCII or binary.
pub(super) trait Values {
    fn next(&mut self, ty: Scalar) -> Result<f64, ReadError>;
    /// The line of the value read last (ASCII only).
    fn line(&self) -> Option<usize>;
    /// Bytes left, to bound allocations by what the file can hold.
    fn remaining(&self) -> usize;
    /// Ends one element's record: an ASCII record is exactly one line, so values left on
    /// it mean the header and the data disagree.
    fn end_record(&mut self) -> Result<(), String> {
        Ok(())
    }
    /// After the last element: data left over means the header's counts are wrong (its
    /// line, where there are lines).
    fn finish(&mut self) -> Result<(), (Option<usize>, String)>;
}

/// What `finish` says of data past the last element.
const DATA_LEFT_OVER: &str = "the data goes on after the last element the header declares \
                              (do the header's element counts match the data?)";

pub(super) struct Binary<'a> {
    pub(super) data: &'a [u8],
    pub(super) pos: usize,
    pub(super) big_endian: bool,
}

impl Binary<'_> {
    pub(super) fn take<const N: usize>(&mut self) -> Result<[u8; N], ReadError> {
        let bytes = self.data.get(self.pos..self.pos + N).ok_or(ReadError::End)?;
        self.pos += N;
        let mut array: [u8; N] = bytes.try_into().expect("N bytes");
        if self.big_endian {
            array.reverse();
        }
        Ok(array)
    }
}

impl Values for Binary<'_> {
    fn next(&mut self, ty: Scalar) -> Result<f64, ReadError> {
        // `take` returns the bytes in little-endian order.
        Ok(match ty {
            Scalar::I8 => i8::from_le_bytes(self.take()?).into(),
            Scalar::U8 => u8::from_le_bytes(self.take()?).into(),
            Scalar::I16 => i16::from_le_bytes(self.take()?).into(),
            Scalar::U16 => u16::from_le_bytes(self.take()?).into(),
            Scalar::I32 => i32::from_le_bytes(self.take()?).into(),
            Scalar::U32 => u32::from_le_bytes(self.take()?).into(),
            Scalar::F32 => f32::from_le_bytes(self.take()?).into(),
            Scalar::F64 => f64::from_le_bytes(self.take()?),
        })
    }

    fn line(&self) -> Option<usize> {
        None
    }

    fn remaining(&self) -> usize {
        self.data.len().saturating_sub(self.pos)
    }

    /// Bytes left over are refused, but for a line end or spaces some writers add.
    fn finish(&mut self) -> Result<(), (Option<usize>, String)> {
        let rest = self.data.get(self.pos..).unwrap_or_default();
        if rest.iter().all(u8::is_ascii_whitespace) {
            return Ok(());
        }
        Err((None, format!("{DATA_LEFT_OVER}: {} bytes are left", rest.len())))
    }
}

pub(super) struct Ascii<'a> {
    pub(super) lines: std::str::Lines<'a>,
    pub(super) words: std::str::SplitWhitespace<'a>,
    /// Line of the current `words`.
    pub(super) line: usize,
    pub(super) remaining: usize,
    /// A value of the current record was read (its line may not end before the record).
    pub(super) in_record: bool,
}

impl Values for Ascii<'_> {
    fn next(&mut self, ty: Scalar) -> Result<f64, ReadError> {
        let word = loop {
            if let Some(word) = self.words.next() {
                break word;
            }
            if self.in_record {
                return Err(ReadError::Bad(
                    "the line ends before the element's properties do (the header declares \
                     more properties than the line has values)"
                        .to_owned(),
                ));
            }
            let line = self.lines.next().ok_or(ReadError::End)?;
            self.remaining = self.remaining.saturating_sub(line.len() + 1);
            self.words = line.split_whitespace();
            self.line += 1;
        };
        self.in_record = true;
        let bad = || {
            let shown = crate::excerpt::excerpt(word);
            ReadError::Bad(format!("'{shown}' is not a valid {}", type_name(ty)))
        };
        // Rust parses "nan" and "inf" too: those are caught as non-finite values later.
        let value: f64 = word.parse().map_err(|_| bad())?;
        if ty.is_integer() {
            let (min, max) = ty.range();
            if value.fract() != 0.0 || value < min || value > max {
                return Err(bad());
            }
        }
        Ok(value)
    }

    fn line(&self) -> Option<usize> {
        Some(self.line)
    }

    fn remaining(&self) -> usize {
        self.remaining
    }

    fn end_record(&mut self) -> Result<(), String> {
        self.in_record = false;
        match self.words.next() {
            Some(word) => Err(format!(
                "the line has more values than the element's properties ('{}' is left over); \
                 each element of an ASCII PLY file takes one line",
                crate::excerpt::excerpt(word)
            )),
            None => Ok(()),
        }
    }

    fn finish(&mut self) -> Result<(), (Option<usize>, String)> {
        for line in self.lines.by_ref() {
            self.line += 1;
            if !line.trim().is_empty() {
                return Err((Some(self.line), DATA_LEFT_OVER.to_owned()));
            }
        }
        Ok(())
    }
}
