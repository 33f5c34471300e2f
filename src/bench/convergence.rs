//! `embray bench convergence`: how fast a render's error falls with samples per pixel,
//! against a reference image, and what that costs in time. For an unbiased renderer
//! MSE × seconds is constant: it is the time-to-equal-error figure (lower is better), the
//! one that compares renderers and samplers fairly.

use crate::film::Film;
use crate::render::{RenderError, RenderOptions, render};
use crate::scene::SceneDesc;
use std::path::Path;

/// One spp of a convergence run.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct ConvergenceRow {
    pub spp: u32,
    /// Render seconds (BVH build excluded).
    pub seconds: f64,
    /// Root mean square error over the R, G, B values of every pixel.
    pub rmse: f64,
    /// MSE × seconds: the time-to-equal-error figure.
    pub mse_seconds: f64,
}

#[derive(Debug, thiserror::Error)]
pub enum ConvergenceError {
    /// `role`: what the file is to the command (the reference, the variance, the input).
    #[error("cannot read the {role} '{path}': {message}")]
    Reference { role: &'static str, path: String, message: String },
    #[error("the reference '{path}' is {got_w}×{got_h}, the scene renders {want_w}×{want_h}")]
    Size { path: String, got_w: u32, got_h: u32, want_w: u32, want_h: u32 },
    #[error(
        "the reference '{path}' has {count} pixel(s) with a NaN or infinite value (the first \
         at x {x}, y {y}); an error measured against it would be meaningless"
    )]
    NonFinite { path: String, count: usize, x: u32, y: u32 },
    #[error(transparent)]
    Render(#[from] RenderError),
}

/// The linear RGB of an EXR (its `R`, `G`, `B` channels) as a film.
pub fn read_reference(path: &Path) -> Result<Film, ConvergenceError> {
    read_linear_exr(path, "reference")
}

/// `read_reference` of a file that is the command's `role` (named in its errors).
pub fn read_linear_exr(path: &Path, role: &'static str) -> Result<Film, ConvergenceError> {
    let error = |message: String| ConvergenceError::Reference {
        role,
        path: path.display().to_string(),
        message,
    };
    // Through the capped reader: only a regular file, of bounded size, recorded as an input
    // so that no output of the run may overwrite it.
    let bytes = crate::input_file::read_bytes(path).map_err(|e| error(e.to_string()))?;
    // The header's size is checked before the reader allocates for it: a render's size at
    // most, as any image embray wrote is.
    let (w, h) = crate::exr_rgb::size(&bytes).map_err(error)?;
    let max = u64::from(crate::scene::MAX_RESOLUTION);
    if w == 0 || h == 0 || w > max || h > max {
        return Err(error(format!("{w} × {h} pixels; images of 1 to {max} on a side are read")));
    }
    let (w, h, pixels) = crate::exr_rgb::read(&bytes).map_err(error)?;
    let mut film = Film::new(w, h);
    film.color = pixels;
    Ok(film)
}

/// Root mean square error of `film` against `reference` over every R, G, B value.
pub fn rmse(film: &Film, reference: &Film) -> f64 {
    let sum: f64 = film
        .color
        .iter()
        .zip(&reference.color)
        .map(|(a, b)| (*a - *b).as_dvec3().length_squared())
        .sum();
    (sum / (3 * film.color.len().max(1)) as f64).sqrt()
}

/// Renders `scene` at each of `spps` with `options` and measures each against `reference`.
pub fn measure(
    scene: &SceneDesc,
    options: &RenderOptions,
    reference: &Film,
    spps: &[u32],
    reference_path: &Path,
) -> Result<Vec<ConvergenceRow>, ConvergenceError> {
    let (w, h) = (scene.camera.width, scene.camera.height);
    if (reference.width, reference.height) != (w, h) {
        return Err(ConvergenceError::Size {
            path: reference_path.display().to_string(),
            got_w: reference.width,
            got_h: reference.height,
            want_w: w,
            want_h: h,
        });
    }
    // Checked before any render: a NaN in the reference would make every row NaN.
    if let Some(bad) = reference.non_finite() {
        let (x, y) = bad.first;
        return Err(ConvergenceError::NonFinite {
            path: reference_path.display().to_string(),
            count: bad.count,
            x,
            y,
        });
    }
    let mut rows = Vec::new();
    for &spp in spps {
        let mut o = options.clone();
        o.spp = spp;
        let out = render(scene, &o)?;
        let seconds = out.render_time.as_secs_f64();
        let rmse = rmse(&out.film, reference);
        rows.push(ConvergenceRow { spp, seconds, rmse, mse_seconds: rmse * rmse * seconds });
    }
    Ok(rows)
}

/// The spp at which the error would reach `target` RMSE, from the last row (MSE ∝ 1/spp
/// for an unbiased estimator).
pub fn spp_for_rmse(rows: &[ConvergenceRow], target: f64) -> Option<f64> {
    let last = rows.last()?;
    (target > 0.0).then(|| last.spp as f64 * (last.rmse / target).powi(2))
}

pub fn markdown(rows: &[ConvergenceRow]) -> String {
    let mut out = String::from("| spp | render s | RMSE | MSE × s |\n|---:|---:|---:|---:|\n");
    for r in rows {
        out +=
            &format!("| {} | {:.3} | {:.5} | {:.3e} |\n", r.spp, r.seconds, r.rmse, r.mse_seconds);
    }
    out
}

pub fn csv(rows: &[ConvergenceRow]) -> String {
    let mut out = String::from("spp,render_seconds,rmse,mse_seconds\n");
    for r in rows {
        out += &format!("{},{},{},{}\n", r.spp, r.seconds, r.rmse, r.mse_seconds);
    }
    out
}
