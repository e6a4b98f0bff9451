//! Binary `<DataArray>` blocks of the `.vtu` reader: number types, the block
//! header, zlib inflation capped by what the array may hold, and base64.

use std::cell::Cell;
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
    /// No values yet, room for `n` of type `ty`; an error instead of an abort
    /// when that room cannot be had.
    pub(super) fn with_capacity(ty: Ty, n: usize) -> std::result::Result<Values, BlockError> {
        let failed = |_| (0, format!("cannot allocate memory for {n} values"));
        Ok(if ty.is_float() {
            let mut v = Vec::new();
            v.try_reserve_exact(n).map_err(failed)?;
            Values::Float(v)
        } else {
            let mut v = Vec::new();
            v.try_reserve_exact(n).map_err(failed)?;
            Values::Int(v)
        })
    }

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

    /// Appends the values stored in `data` (a whole number of them) as `ty`.
    fn append(
        &mut self,
        ty: Ty,
        big_endian: bool,
        data: &[u8],
    ) -> std::result::Result<(), BlockError> {
        let size = ty.size();
        let n = data.len() / size;
        let failed = |_| (0, format!("cannot allocate memory for {n} more values"));
        match self {
            Values::Int(v) => v.try_reserve(n).map_err(failed)?,
            Values::Float(v) => v.try_reserve(n).map_err(failed)?,
        }
        macro_rules! conv {
            ($t:ty) => {
                data.chunks_exact(size).map(|c| {
                    let b = c.try_into().expect("chunk of the type's size");
                    if big_endian {
                        <$t>::from_be_bytes(b)
                    } else {
                        <$t>::from_le_bytes(b)
                    }
                })
            };
        }
        match (self, ty) {
            (Values::Int(v), Ty::I8) => v.extend(conv!(i8).map(i64::from)),
            (Values::Int(v), Ty::U8) => v.extend(conv!(u8).map(i64::from)),
            (Values::Int(v), Ty::I16) => v.extend(conv!(i16).map(i64::from)),
            (Values::Int(v), Ty::U16) => v.extend(conv!(u16).map(i64::from)),
            (Values::Int(v), Ty::I32) => v.extend(conv!(i32).map(i64::from)),
            (Values::Int(v), Ty::U32) => v.extend(conv!(u32).map(i64::from)),
            (Values::Int(v), Ty::I64) => v.extend(conv!(i64)),
            (Values::Int(v), Ty::U64) => {
                for x in conv!(u64) {
                    let x = i64::try_from(x)
                        .map_err(|_| (0, format!("UInt64 value {x} is too large")))?;
                    v.push(x);
                }
            }
            (Values::Float(v), Ty::F32) => v.extend(conv!(f32).map(f64::from)),
            (Values::Float(v), Ty::F64) => v.extend(conv!(f64)),
            _ => unreachable!("values are made for their type"),
        }
        Ok(())
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

/// How many bytes the values of all zlib blocks of a file may take once
/// decoded (8 bytes a value, whatever its type): 64 MiB plus 64 times the
/// file's size. Meshes compress by a few times; a stream of zeros by a
/// thousand.
pub(super) fn inflate_budget(file_size: usize) -> u64 {
    (64 << 20) + 64 * file_size as u64
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

    /// The values of type `ty` in a binary block `s` (header, then data):
    /// sliced out, or inflated block by block when zlib-compressed; `None`
    /// when the header claims more than `max` values (nothing is inflated
    /// then). The values zlib blocks claim are taken from `budget` (8 bytes
    /// each) before they are inflated, and no block inflates past its claim.
    pub(super) fn block_values(
        &self,
        s: &[u8],
        ty: Ty,
        max: usize,
        budget: &Cell<u64>,
    ) -> std::result::Result<Option<Values>, BlockError> {
        let h = if self.header64 { 8 } else { 4 };
        let size = ty.size();
        let max = max.saturating_mul(size);
        let too_long = |at: usize, claim: u64| {
            (
                at,
                format!(
                    "truncated: header claims {claim} bytes but only {} remain",
                    s.len().saturating_sub(at)
                ),
            )
        };
        let not_whole = |n: u64| {
            (
                0,
                format!("{n} bytes is not a whole number of {size}-byte values"),
            )
        };
        if !self.zlib {
            let n = self.word(s, 0)?;
            let data = match usize::try_from(n) {
                Ok(n) if n > max => return Ok(None),
                Ok(n) if n <= s.len() - h => &s[h..h + n],
                _ => return Err(too_long(h, n)),
            };
            if data.len() % size != 0 {
                return Err(not_whole(n));
            }
            let mut values = Values::with_capacity(ty, data.len() / size)?;
            values.append(ty, self.big_endian, data)?;
            return Ok(Some(values));
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
        let size_of = |k: usize| {
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
                .and_then(|b| b.checked_add(size_of(count - 1))),
        };
        // 8 bytes a value once decoded: more than the budget left is an
        // error, more than `max` values is left to the caller.
        let decoded = claimed.map_or(u64::MAX, |c| (c / size as u64).saturating_mul(8));
        if decoded > budget.get() {
            return Err((
                0,
                format!(
                    "zlib blocks claiming {} bytes ({} bytes once decoded) exceed what is \
                     left ({} bytes) of the file's budget for zlib data (64 MiB plus 64 times \
                     the file's size)",
                    claimed.map_or("more than 2^64".to_string(), |c| c.to_string()),
                    claimed.map_or("more than 2^64".to_string(), |_| decoded.to_string()),
                    budget.get()
                ),
            ));
        }
        let claimed = match claimed {
            Some(c) if c <= max as u64 => c,
            _ => return Ok(None),
        };
        if claimed % size as u64 != 0 {
            return Err(not_whole(claimed));
        }
        budget.set(budget.get() - decoded);
        // Deflate inflates at most 1032 times: what the data can hold is
        // reserved, not what a lying header claims.
        let can_hold = (s.len() - header) as u64 * 1032 + 64;
        let mut values = Values::with_capacity(ty, claimed.min(can_hold) as usize / size)?;
        let mut start = header;
        let mut buf = vec![0u8; 1 << 16];
        // Bytes of a value split between two reads.
        let mut carry = Vec::with_capacity(size);
        for k in 0..count {
            let bytes = self.word(s, (3 + k) * h)?;
            let end = match usize::try_from(bytes) {
                Ok(bytes) if bytes <= s.len() - start => start + bytes,
                _ => return Err(too_long(start, bytes)),
            };
            let expected = size_of(k);
            let mut z = flate2::read::ZlibDecoder::new(&s[start..end]).take(expected + 1);
            let mut inflated = 0u64;
            loop {
                let n = z
                    .read(&mut buf)
                    .map_err(|e| (start, format!("zlib block {k}: {e}")))?;
                if n == 0 {
                    break;
                }
                inflated += n as u64;
                if inflated > expected {
                    break;
                }
                let mut chunk = &buf[..n];
                if !carry.is_empty() {
                    let take = (size - carry.len()).min(chunk.len());
                    carry.extend_from_slice(&chunk[..take]);
                    chunk = &chunk[take..];
                    if carry.len() == size {
                        values.append(ty, self.big_endian, &carry)?;
                        carry.clear();
                    }
                }
                let whole = chunk.len() / size * size;
                values.append(ty, self.big_endian, &chunk[..whole])?;
                carry.extend_from_slice(&chunk[whole..]);
            }
            if inflated != expected {
                return Err((
                    start,
                    format!("zlib block {k} inflates to {inflated} bytes (header says {expected})"),
                ));
            }
            start = end;
        }
        Ok(Some(values))
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
