//! Binary `<DataArray>` blocks of the `.vtu` reader: number types, the block
//! header, zlib inflation capped by what the array may hold, and base64.

use std::borrow::Cow;
use std::io::Read;

use base64::engine::general_purpose::{GeneralPurpose, GeneralPurposeConfig};
use base64::engine::DecodePaddingMode;
use base64::Engine;

/// A number type found in a `type` attribute.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Ty {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    I64,
    U64,
    F32,
    F64,
}

impl Ty {
    pub(super) fn parse(s: &str) -> Option<Ty> {
        Some(match s {
            "Int8" => Ty::I8,
            "UInt8" => Ty::U8,
            "Int16" => Ty::I16,
            "UInt16" => Ty::U16,
            "Int32" => Ty::I32,
            "UInt32" => Ty::U32,
            "Int64" => Ty::I64,
            "UInt64" => Ty::U64,
            "Float32" => Ty::F32,
            "Float64" => Ty::F64,
            _ => return None,
        })
    }

    pub(super) fn size(self) -> usize {
        match self {
            Ty::I8 | Ty::U8 => 1,
            Ty::I16 | Ty::U16 => 2,
            Ty::I32 | Ty::U32 | Ty::F32 => 4,
            Ty::I64 | Ty::U64 | Ty::F64 => 8,
        }
    }

    pub(super) fn is_float(self) -> bool {
        matches!(self, Ty::F32 | Ty::F64)
    }
}

/// The values of one array.
pub(super) enum Values {
    Int(Vec<i64>),
    Float(Vec<f64>),
}

impl Values {
    pub(super) fn len(&self) -> usize {
        match self {
            Values::Int(v) => v.len(),
            Values::Float(v) => v.len(),
        }
    }

    pub(super) fn into_f64(self) -> Vec<f64> {
        match self {
            Values::Int(v) => v.into_iter().map(|x| x as f64).collect(),
            Values::Float(v) => v,
        }
    }
}

/// A failure inside a binary block: offset in the block's byte stream, message.
pub(super) type BlockError = (usize, String);

/// How the file lays out binary blocks (attributes of `<VTKFile>`).
#[derive(Clone, Copy)]
pub(super) struct Layout {
    pub(super) big_endian: bool,
    pub(super) header64: bool,
    pub(super) zlib: bool,
}

impl Layout {
    /// Reads one header word (4 or 8 bytes) at byte `at` of a block.
    fn word(&self, s: &[u8], at: usize) -> std::result::Result<u64, BlockError> {
        let size = if self.header64 { 8 } else { 4 };
        let b = s.get(at..at + size).ok_or_else(|| {
            (
                at,
                format!(
                    "truncated: header needs {size} bytes, {} remain",
                    s.len().saturating_sub(at)
                ),
            )
        })?;
        Ok(match (self.header64, self.big_endian) {
            (true, false) => u64::from_le_bytes(b.try_into().expect("8 bytes")),
            (true, true) => u64::from_be_bytes(b.try_into().expect("8 bytes")),
            (false, false) => u32::from_le_bytes(b.try_into().expect("4 bytes")).into(),
            (false, true) => u32::from_be_bytes(b.try_into().expect("4 bytes")).into(),
        })
    }

    /// The data bytes of a binary block `s` (header, then data): sliced out,
    /// or inflated block by block when zlib-compressed; `None` when the
    /// header claims more than `max` bytes (nothing is inflated then).
    fn block<'s>(
        &self,
        s: &'s [u8],
        max: usize,
    ) -> std::result::Result<Option<Cow<'s, [u8]>>, BlockError> {
        let h = if self.header64 { 8 } else { 4 };
        let too_long = |at: usize, claim: u64| {
            (
                at,
                format!(
                    "truncated: header claims {claim} bytes but only {} remain",
                    s.len().saturating_sub(at)
                ),
            )
        };
        if !self.zlib {
            let n = self.word(s, 0)?;
            return match usize::try_from(n) {
                Ok(n) if n > max => Ok(None),
                Ok(n) if n <= s.len() - h => Ok(Some(Cow::Borrowed(&s[h..h + n]))),
                _ => Err(too_long(h, n)),
            };
        }
        let blocks = self.word(s, 0)?;
        let full = self.word(s, h)?;
        let last = self.word(s, 2 * h)?;
        let count = usize::try_from(blocks).ok();
        let header = count.and_then(|b| b.checked_add(3)?.checked_mul(h));
        let (count, header) = match (count, header) {
            (Some(b), Some(header)) if header <= s.len() => (b, header),
            _ => return Err(too_long(3 * h, blocks.saturating_mul(h as u64))),
        };
        // What the header says the blocks inflate to, checked before inflating.
        let size = |k: usize| {
            if k + 1 == count && last != 0 {
                last
            } else {
                full
            }
        };
        let claimed = match count {
            0 => Some(0),
            _ => full
                .checked_mul(blocks - 1)
                .and_then(|b| b.checked_add(size(count - 1))),
        };
        if claimed.is_none_or(|c| c > max as u64) {
            return Ok(None);
        }
        let mut start = header;
        let mut out = Vec::new();
        for k in 0..count {
            let bytes = self.word(s, (3 + k) * h)?;
            let end = match usize::try_from(bytes) {
                Ok(bytes) if bytes <= s.len() - start => start + bytes,
                _ => return Err(too_long(start, bytes)),
            };
            let expected = size(k);
            let before = out.len();
            flate2::read::ZlibDecoder::new(&s[start..end])
                .take(expected.saturating_add(1))
                .read_to_end(&mut out)
                .map_err(|e| (start, format!("zlib block {k}: {e}")))?;
            if (out.len() - before) as u64 != expected {
                return Err((
                    start,
                    format!(
                        "zlib block {k} inflates to {} bytes (header says {expected})",
                        out.len() - before
                    ),
                ));
            }
            start = end;
        }
        Ok(Some(Cow::Owned(out)))
    }

    /// The values of a binary block, `None` when it holds more than `max`.
    pub(super) fn block_values(
        &self,
        s: &[u8],
        ty: Ty,
        max: usize,
    ) -> std::result::Result<Option<Values>, BlockError> {
        let size = ty.size();
        let Some(data) = self.block(s, max.saturating_mul(size))? else {
            return Ok(None);
        };
        if data.len() % size != 0 {
            return Err((
                0,
                format!(
                    "{} bytes is not a whole number of {size}-byte values",
                    data.len()
                ),
            ));
        }
        let be = self.big_endian;
        macro_rules! conv {
            ($t:ty) => {
                data.chunks_exact(size).map(|c| {
                    let b = c.try_into().expect("chunk of the type's size");
                    if be {
                        <$t>::from_be_bytes(b)
                    } else {
                        <$t>::from_le_bytes(b)
                    }
                })
            };
        }
        Ok(Some(match ty {
            Ty::I8 => Values::Int(conv!(i8).map(i64::from).collect()),
            Ty::U8 => Values::Int(conv!(u8).map(i64::from).collect()),
            Ty::I16 => Values::Int(conv!(i16).map(i64::from).collect()),
            Ty::U16 => Values::Int(conv!(u16).map(i64::from).collect()),
            Ty::I32 => Values::Int(conv!(i32).map(i64::from).collect()),
            Ty::U32 => Values::Int(conv!(u32).map(i64::from).collect()),
            Ty::I64 => Values::Int(conv!(i64).collect()),
            Ty::U64 => Values::Int(
                conv!(u64)
                    .map(|v| {
                        i64::try_from(v).map_err(|_| (0, format!("UInt64 value {v} is too large")))
                    })
                    .collect::<std::result::Result<_, _>>()?,
            ),
            Ty::F32 => Values::Float(conv!(f32).map(f64::from).collect()),
            Ty::F64 => Values::Float(conv!(f64).collect()),
        }))
    }
}

/// Decodes base64 text made of one or more padded segments (VTK encodes a
/// header and its data separately, meshio sometimes together): the bytes of
/// all segments, one after the other.
pub(super) fn decode_base64(text: &[u8]) -> std::result::Result<Vec<u8>, BlockError> {
    const ENGINE: GeneralPurpose = GeneralPurpose::new(
        &base64::alphabet::STANDARD,
        GeneralPurposeConfig::new()
            .with_decode_allow_trailing_bits(true)
            .with_decode_padding_mode(DecodePaddingMode::Indifferent),
    );
    let mut out = Vec::with_capacity(text.len() / 4 * 3);
    let mut start = 0;
    while start < text.len() {
        let end = text[start..]
            .iter()
            .position(|&b| b == b'=')
            .map_or(text.len(), |p| ((start + p) / 4 + 1) * 4)
            .min(text.len());
        ENGINE
            .decode_vec(&text[start..end], &mut out)
            .map_err(|e| match e {
                base64::DecodeError::InvalidByte(i, b)
                | base64::DecodeError::InvalidLastSymbol(i, b) => (
                    start + i,
                    format!(
                        "invalid base64 character '{}' at position {}",
                        b.escape_ascii(),
                        start + i
                    ),
                ),
                _ => (
                    end,
                    format!("base64 data of {} characters is cut short", text.len()),
                ),
            })?;
        start = end;
    }
    Ok(out)
}
