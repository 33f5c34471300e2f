//! Mitsuba's grid volume file (`.vol`, version 3): "VOL", a version byte (3), then
//! little-endian i32 encoding (1: float32), x, y and z sizes and the channel count, six f32
//! of bounding box (min, max), and the values, x fastest, each voxel's channels together.
//!
//! The header's count of values is checked against the caller's limit and then against
//! the file's length before anything is allocated, so a hostile header cannot ask for more
//! memory than the file holds.

/// A grid read from a `.vol` file.
#[derive(Clone, Debug, PartialEq)]
pub struct VolGrid {
    pub size: [u32; 3],
    pub channels: u32,
    /// `size[0] · size[1] · size[2] · channels` values.
    pub values: Vec<f32>,
}

const HEADER_BYTES: usize = 48;

fn i32_at(bytes: &[u8], offset: usize) -> i32 {
    let mut word = [0u8; 4];
    word.copy_from_slice(&bytes[offset..offset + 4]);
    i32::from_le_bytes(word)
}

/// Parses `bytes` as a `.vol` file of at most `max_values` values (all channels); the
/// error says what is wrong (the caller names the file).
pub fn parse(bytes: &[u8], max_values: u64) -> Result<VolGrid, String> {
    if bytes.len() < HEADER_BYTES {
        return Err(format!(
            "{} bytes, shorter than a .vol header ({HEADER_BYTES} bytes)",
            bytes.len()
        ));
    }
    if &bytes[..3] != b"VOL" {
        return Err("not a .vol file (it does not start with \"VOL\")".into());
    }
    if bytes[3] != 3 {
        return Err(format!("version {} (only version 3 is read)", bytes[3]));
    }
    let encoding = i32_at(bytes, 4);
    if encoding != 1 {
        return Err(format!("encoding {encoding} (only 1, float32, is read)"));
    }
    let dimension = |index: usize, name: &str| -> Result<u32, String> {
        let value = i32_at(bytes, 8 + 4 * index);
        u32::try_from(value)
            .ok()
            .filter(|&v| v > 0)
            .ok_or_else(|| format!("{name} is {value}, but must be > 0"))
    };
    let size = [dimension(0, "x size")?, dimension(1, "y size")?, dimension(2, "z size")?];
    let channels = dimension(3, "the channel count")?;
    let count = size
        .iter()
        .chain([&channels])
        .try_fold(1u64, |n, &d| n.checked_mul(u64::from(d)))
        .filter(|&n| n <= (usize::MAX / 4) as u64);
    if count.is_none_or(|n| n > max_values) {
        let [x, y, z] = size;
        return Err(format!(
            "the header says {x}×{y}×{z} values of {channels} channel(s), but a grid holds at \
             most {max_values} values"
        ));
    }
    let expected = count.map(|n| n * 4 + HEADER_BYTES as u64);
    if expected != Some(bytes.len() as u64) {
        let [x, y, z] = size;
        let wanted = expected.map_or("more than can be addressed".to_owned(), |n| n.to_string());
        return Err(format!(
            "the header says {x}×{y}×{z} values of {channels} channel(s) ({wanted} bytes), but \
             the file has {} bytes",
            bytes.len()
        ));
    }
    let values: Vec<f32> = bytes[HEADER_BYTES..]
        .chunks_exact(4)
        .map(|w| f32::from_le_bytes([w[0], w[1], w[2], w[3]]))
        .collect();
    Ok(VolGrid { size, channels, values })
}

/// The bytes of a `.vol` file holding `values` (one channel).
#[cfg(test)]
fn write_single_channel(size: [u32; 3], values: &[f32]) -> Vec<u8> {
    let mut bytes = b"VOL\x03".to_vec();
    for word in [1, size[0] as i32, size[1] as i32, size[2] as i32, 1] {
        bytes.extend(word.to_le_bytes());
    }
    for bound in [0.0f32, 0.0, 0.0, 1.0, 1.0, 1.0] {
        bytes.extend(bound.to_le_bytes());
    }
    for v in values {
        bytes.extend(v.to_le_bytes());
    }
    bytes
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_what_it_writes() {
        let values: Vec<f32> = (0..24).map(|i| i as f32 - 3.5).collect();
        let grid = parse(&write_single_channel([2, 3, 4], &values), 24).unwrap();
        assert_eq!((grid.size, grid.channels, grid.values), ([2, 3, 4], 1, values));
    }

    #[test]
    fn refuses_sizes_the_file_does_not_hold() {
        let parse = |bytes: &[u8]| parse(bytes, u64::MAX);
        let mut bytes = write_single_channel([2, 2, 2], &[1.0; 8]);
        assert!(parse(&bytes[..bytes.len() - 1]).unwrap_err().contains("the file has 79 bytes"));
        bytes[8..12].copy_from_slice(&i32::MAX.to_le_bytes());
        assert!(parse(&bytes).unwrap_err().contains("2147483647×2×2"));
        bytes[8..12].copy_from_slice(&(-2i32).to_le_bytes());
        assert!(parse(&bytes).unwrap_err().contains("x size is -2"));
        assert!(parse(b"VOL").unwrap_err().contains("shorter than"));
        let mut wrong = write_single_channel([1, 1, 1], &[0.0]);
        wrong[3] = 2;
        assert!(parse(&wrong).unwrap_err().contains("version 2"));
        wrong[3] = 3;
        wrong[4] = 2;
        assert!(parse(&wrong).unwrap_err().contains("encoding 2"));
    }

    /// The limit is checked on the header's count, before the file's length or any value.
    #[test]
    fn refuses_a_header_over_the_limit_before_reading() {
        let bytes = write_single_channel([2, 2, 2], &[1.0; 8]);
        assert!(parse(&bytes, 7).unwrap_err().contains("at most 7 values"));
        assert!(parse(&bytes[..HEADER_BYTES], 7).unwrap_err().contains("at most 7 values"));
        assert_eq!(parse(&bytes, 8).unwrap().values.len(), 8);
    }
}
