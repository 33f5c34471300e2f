//! Perlin's improved gradient noise (Perlin 2002, "Improving Noise"): the reference
//! permutation, the 12 cube-edge gradients (padded to 16 as in the paper) and the quintic
//! fade, giving values in about [-1, 1] that are 0 at every lattice point.

use glam::Vec3;

/// Ken Perlin's reference permutation of 0..=255.
const PERMUTATION: [u8; 256] = [
    151, 160, 137, 91, 90, 15, 131, 13, 201, 95, 96, 53, 194, 233, 7, 225, 140, 36, 103, 30, 69,
    142, 8, 99, 37, 240, 21, 10, 23, 190, 6, 148, 247, 120, 234, 75, 0, 26, 197, 62, 94, 252, 219,
    203, 117, 35, 11, 32, 57, 177, 33, 88, 237, 149, 56, 87, 174, 20, 125, 136, 171, 168, 68, 175,
    74, 165, 71, 134, 139, 48, 27, 166, 77, 146, 158, 231, 83, 111, 229, 122, 60, 211, 133, 230,
    220, 105, 92, 41, 55, 46, 245, 40, 244, 102, 143, 54, 65, 25, 63, 161, 1, 216, 80, 73, 209, 76,
    132, 187, 208, 89, 18, 169, 200, 196, 135, 130, 116, 188, 159, 86, 164, 100, 109, 198, 173,
    186, 3, 64, 52, 217, 226, 250, 124, 123, 5, 202, 38, 147, 118, 126, 255, 82, 85, 212, 207, 206,
    59, 227, 47, 16, 58, 17, 182, 189, 28, 42, 223, 183, 170, 213, 119, 248, 152, 2, 44, 154, 163,
    70, 221, 153, 101, 155, 167, 43, 172, 9, 129, 22, 39, 253, 19, 98, 108, 110, 79, 113, 224, 232,
    178, 185, 112, 104, 218, 246, 97, 228, 251, 34, 242, 193, 238, 210, 144, 12, 191, 179, 162,
    241, 81, 51, 145, 235, 249, 14, 239, 107, 49, 192, 214, 31, 181, 199, 106, 157, 184, 84, 204,
    176, 115, 121, 50, 45, 127, 4, 150, 254, 138, 236, 205, 93, 222, 114, 67, 29, 24, 72, 243, 141,
    128, 195, 78, 66, 215, 61, 156, 180,
];

fn hash(i: i64) -> usize {
    PERMUTATION[(i & 255) as usize] as usize
}

/// The dot product of lattice gradient number `h` with the offset `d`.
fn gradient_dot(h: usize, d: Vec3) -> f32 {
    match h & 15 {
        0 | 12 => d.x + d.y,
        1 | 14 => -d.x + d.y,
        2 => d.x - d.y,
        3 => -d.x - d.y,
        4 => d.x + d.z,
        5 => -d.x + d.z,
        6 => d.x - d.z,
        7 => -d.x - d.z,
        8 => d.y + d.z,
        9 | 13 => -d.y + d.z,
        10 => d.y - d.z,
        _ => -d.y - d.z, // 11, 15
    }
}

/// 6t⁵ − 15t⁴ + 10t³: C² smooth between the lattice cells.
fn fade(t: f32) -> f32 {
    t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
}

/// Noise at `p`, in about [-1, 1].
pub fn noise(p: Vec3) -> f32 {
    let cell = p.floor();
    let d = p - cell;
    let [x, y, z] = [cell.x as i64, cell.y as i64, cell.z as i64];
    let w = Vec3::new(fade(d.x), fade(d.y), fade(d.z));
    let corner = |i: i64, j: i64, k: i64| {
        let h = hash(x + i + hash(y + j + hash(z + k) as i64) as i64);
        gradient_dot(h, d - Vec3::new(i as f32, j as f32, k as f32))
    };
    let lerp = |t: f32, a: f32, b: f32| a + t * (b - a);
    let x00 = lerp(w.x, corner(0, 0, 0), corner(1, 0, 0));
    let x10 = lerp(w.x, corner(0, 1, 0), corner(1, 1, 0));
    let x01 = lerp(w.x, corner(0, 0, 1), corner(1, 0, 1));
    let x11 = lerp(w.x, corner(0, 1, 1), corner(1, 1, 1));
    lerp(w.z, lerp(w.y, x00, x10), lerp(w.y, x01, x11))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zero_on_the_lattice_bounded_and_varied_between() {
        assert_eq!(noise(Vec3::new(3.0, -7.0, 12.0)), 0.0);
        let mut values = Vec::new();
        for i in 0..4000 {
            let t = i as f32 * 0.173;
            values.push(noise(Vec3::new(t, t * 0.37 - 5.0, (t * 1.91).sin() * 9.0)));
        }
        assert!(values.iter().all(|v| v.abs() <= 1.05), "out of range");
        let mean = values.iter().sum::<f32>() / values.len() as f32;
        let spread = values.iter().map(|v| (v - mean).powi(2)).sum::<f32>() / values.len() as f32;
        assert!(mean.abs() < 0.05 && spread.sqrt() > 0.15, "mean {mean} sd {}", spread.sqrt());
    }

    #[test]
    fn continuous_across_cell_faces() {
        for &x in &[1.0f32, -3.0, 17.0] {
            let below = noise(Vec3::new(x - 1e-4, 0.3, 0.6));
            let above = noise(Vec3::new(x + 1e-4, 0.3, 0.6));
            assert!((below - above).abs() < 2e-3, "jump at x = {x}: {below} vs {above}");
        }
    }
}
