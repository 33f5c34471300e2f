//! Denoising a render's beauty with Intel Open Image Denoise 2 (the `denoise` feature), as
//! Cycles does: its `RT` filter on the HDR colour, guided by the first hit's albedo and
//! shading normal. The albedo is prefiltered first (OIDN's advice for auxiliary images
//! that carry noise: ours is a mean of as few samples as the beauty, noisy through glass,
//! depth of field or motion); the normal is passed as it is, so the filter is told the
//! auxiliary images are not clean (the oidn crate has no normal-only prefilter).

use crate::film::Film;
use glam::Vec3;

/// Whether this build can denoise.
pub const BUILT_IN: bool = cfg!(feature = "denoise");

/// What denoised an image, for its metadata.
pub const DENOISER: &str =
    "Open Image Denoise 2.5.1, RT filter (HDR), albedo (prefiltered) and normal";

#[derive(Debug, thiserror::Error)]
pub enum DenoiseError {
    #[error(
        "denoising is not built into this embray: `export OIDN_DIR=$(bash \
         scripts/oidn-runtime.sh)`, then build with `--features denoise` (README: Denoising)"
    )]
    NotBuiltIn,
    #[error("Open Image Denoise failed: {0}")]
    Oidn(String),
    #[error(
        "rendering and denoising {estimate} needs about {} MiB, more than the {} MiB \
         available (the denoiser adds {} bytes a pixel; render smaller, on fewer --threads, or without --denoise)",
        .needed >> 20, .available >> 20, crate::limits::DENOISE_BYTES_PER_PIXEL
    )]
    /// (The estimate boxed: every denoising error would otherwise carry its size.)
    Memory { estimate: Box<crate::scene::budget::MemoryEstimate>, needed: u64, available: u64 },
}

/// Refuses, before anything is rendered, a render of `desc` that could not also be denoised
/// in the memory there is (`BackendKind::bytes_per_triangle` as for the render's own check).
pub fn check_memory(
    desc: &crate::scene::SceneDesc,
    bytes_per_triangle: u64,
    threads: usize,
) -> Result<(), DenoiseError> {
    let estimate = crate::scene::budget::memory_needed(desc, bytes_per_triangle, threads);
    let denoiser = estimate.pixels.saturating_mul(crate::limits::DENOISE_BYTES_PER_PIXEL);
    let needed = estimate.bytes.saturating_add(denoiser);
    match crate::limits::memory_available() {
        Some(available) if needed > available => {
            Err(DenoiseError::Memory { estimate: Box::new(estimate), needed, available })
        }
        _ => Ok(()),
    }
}

/// The denoised beauty of `film` (its albedo AOV must have been rendered:
/// `RenderOptions::first_hit_albedo`).
pub fn denoise(film: &Film) -> Result<Vec<Vec3>, DenoiseError> {
    #[cfg(feature = "denoise")]
    {
        // The oidn crate panics where a buffer cannot be made; that is an error here.
        std::panic::catch_unwind(|| with_oidn::denoise(film))
            .unwrap_or_else(|_| Err("a buffer could not be allocated".to_owned()))
            .map_err(DenoiseError::Oidn)
    }
    #[cfg(not(feature = "denoise"))]
    {
        let _ = film;
        Err(DenoiseError::NotBuiltIn)
    }
}

#[cfg(feature = "denoise")]
mod with_oidn {
    use super::{Film, Vec3};

    fn flat(pixels: &[Vec3]) -> Vec<f32> {
        pixels.iter().flat_map(|c| c.to_array()).collect()
    }

    pub(super) fn denoise(film: &Film) -> Result<Vec<Vec3>, String> {
        let failed = |e: oidn::Error| format!("{} ({})", e.kind(), e.message());
        let (width, height) = (film.width as usize, film.height as usize);
        let device = oidn::Device::cpu().map_err(failed)?;
        let mut albedo = flat(&film.albedo);
        let mut prefilter = oidn::RayTracing::try_new(&device).map_err(failed)?;
        prefilter.image_dimensions(width, height).albedo(&albedo);
        prefilter.filter_in_place(&mut albedo).map_err(failed)?;
        let normal = flat(&film.normal);
        let mut beauty = oidn::RayTracing::try_new(&device).map_err(failed)?;
        beauty
            .image_dimensions(width, height)
            .hdr(true)
            .clean_aux(false)
            .albedo_normal(&albedo, &normal);
        let mut out = vec![0.0; width * height * 3];
        beauty.filter(&flat(&film.color), &mut out).map_err(failed)?;
        // Negative or non-finite output (never expected) must not reach the files.
        Ok(out
            .chunks_exact(3)
            .map(|c| Vec3::new(c[0], c[1], c[2]))
            .map(|c| if c.is_finite() { c.max(Vec3::ZERO) } else { Vec3::ZERO })
            .collect())
    }
}
