//! `<Camera>` → `CameraDesc`, the image name and the sample count.
//!
//! The course's camera: w = −normalize(Gaze), u = normalize(Up × w), v = w × u (the same
//! frame `camera::camera_basis` builds from lookfrom/lookat/up), an image window
//! `NearPlane` = l r b t at `NearDistance` along −w, pixel centres at (i + ½, j + ½).
//! A near-plane window is reproduced exactly, off-centre ones included: its height gives the
//! vertical field of view (2·atan((t − b) / 2d)) and its centre the lens shift
//! ((l + r) / 2d, (b + t) / 2d). Pixels stay square, so a window whose aspect differs from
//! the resolution's is noted and the horizontal extent follows the resolution.

use super::xml::Xml;
use crate::output::Photographic;
use crate::scene::MAX_RESOLUTION;
use crate::scene::desc::{CameraDesc, LensShape, MAX_LENS_EXTENT, lens_extent_requirement};
use crate::scene::error::SceneError;
use glam::DVec2;
use roxmltree::Node;

/// One camera of the file: what it renders and where the image goes.
pub(super) struct CameraSpec {
    pub image_name: String,
    pub camera: CameraDesc,
    pub spp: u32,
    /// The `<Tonemap>` of a camera that writes HDR (photographic, the only operator).
    pub tonemap: Option<Photographic>,
    /// `<Renderer>PathTracing</Renderer>` (hw6): this camera renders with the path tracer.
    pub path_tracing: Option<PathTracing>,
    /// Approximations made (off-centre or non-square window).
    pub notes: Vec<String>,
}

const COMMON: [&str; 7] = [
    "Position",
    "Up",
    "NearDistance",
    "ImageResolution",
    "ImageName",
    "NumSamples",
    "ApertureSize",
];

pub(super) fn camera(x: &Xml, node: Node) -> Result<CameraSpec, SceneError> {
    let look_at = match node.attribute("type").map(str::trim) {
        None | Some("") | Some("simple") => false,
        Some(kind) if kind.eq_ignore_ascii_case("lookAt") => true,
        Some(kind) => {
            return Err(x.error(
                node,
                format!("unsupported camera type \"{kind}\" (supported: lookAt, or none)"),
            ));
        }
    };
    let own: &[&str] = if look_at {
        &["GazePoint", "Gaze", "FovY", "FocusDistance", "Tonemap", "Renderer", "RendererParams"]
    } else {
        &["Gaze", "NearPlane", "FocusDistance", "Tonemap", "Renderer", "RendererParams"]
    };
    let allowed: Vec<&str> = COMMON.iter().chain(own).copied().collect();
    x.check_children(node, &allowed)?;
    // The course's frame is right-handed (u = up × w); a left-handed one would mirror it.
    match node.attribute("handedness").map(str::trim) {
        None | Some("right") => {}
        Some(other) => {
            return Err(x.error(
                node,
                format!(
                    "handedness=\"{}\" is not supported (supported: right)",
                    crate::excerpt::excerpt(other)
                ),
            ));
        }
    }

    let position = x.vec3(x.required(node, "Position")?)?;
    let up_node = x.required(node, "Up")?;
    let up = x.vec3(up_node)?;
    if up.try_normalize().is_none() {
        return Err(x.out_of_range(up_node, "0 0 0", "a non-zero vector"));
    }
    let resolution_node = x.required(node, "ImageResolution")?;
    let [w, h] = x.numbers::<2>(resolution_node, false)?;
    for value in [w, h] {
        if value.fract() != 0.0 || !(1.0..=MAX_RESOLUTION as f64).contains(&value) {
            return Err(x.out_of_range(
                resolution_node,
                value,
                &format!("a whole number between 1 and {MAX_RESOLUTION}"),
            ));
        }
    }
    let (width, height) = (w as u32, h as u32);
    let name_node = x.required(node, "ImageName")?;
    let image_name = x.text(name_node).to_owned();
    if image_name.is_empty() {
        return Err(x.error(name_node, "the image name is empty"));
    }
    if let Some(problem) = crate::output::image_name_problem(&image_name) {
        return Err(x.error(name_node, problem));
    }
    let spp = match x.child(node, "NumSamples")? {
        Some(n) => {
            let spp = x.count(n)?;
            let max = crate::limits::MAX_SPP;
            if !(1..=u64::from(max)).contains(&spp) {
                return Err(x.out_of_range(n, spp, &format!("between 1 and {max}")));
            }
            spp as u32
        }
        None => 1,
    };
    let near_distance = optional_positive(x, node, "NearDistance")?;

    let mut notes = Vec::new();
    let (gaze, vfov_deg, shift, pixel_aspect) = if look_at {
        // A lookAt camera looks at a GazePoint or along a Gaze direction (hw6), not both.
        let gaze_point = match (x.child(node, "GazePoint")?, x.child(node, "Gaze")?) {
            (Some(point), None) => x.vec3(point)?,
            (None, Some(direction)) => position + x.vec3(direction)?,
            (Some(_), Some(direction)) => {
                return Err(x.error(direction, "give either <GazePoint> or <Gaze>, not both"));
            }
            (None, None) => return Err(x.missing(node, "GazePoint")),
        };
        let fov_node = x.required(node, "FovY")?;
        let fov = x.scalar(fov_node)?;
        if !(fov > 0.0 && fov < 180.0) {
            return Err(x.out_of_range(fov_node, fov, "between 0 and 180 degrees (exclusive)"));
        }
        let gaze = gaze_point - position;
        if gaze.try_normalize().is_none() {
            return Err(x.error(node, "<GazePoint> is the same point as <Position>"));
        }
        (gaze, fov, DVec2::ZERO, 1.0)
    } else {
        let gaze_node = x.required(node, "Gaze")?;
        let gaze = x.vec3(gaze_node)?;
        if gaze.try_normalize().is_none() {
            return Err(x.out_of_range(gaze_node, "0 0 0", "a non-zero vector"));
        }
        let plane_node = x.required(node, "NearPlane")?;
        let [l, r, b, t] = x.numbers::<4>(plane_node, true)?;
        if !(r > l && t > b) {
            return Err(x.out_of_range(
                plane_node,
                format!("{l} {r} {b} {t}"),
                "left < right and bottom < top",
            ));
        }
        let Some(d) = near_distance else {
            return Err(x.missing(node, "NearDistance"));
        };
        let window = Window { l, r, b, t, d };
        let (vfov, shift, pixel_aspect) = window.projection((width, height));
        if !(1e-3..=1e3).contains(&pixel_aspect) {
            let requirement = "an aspect within 1000× of the resolution's";
            return Err(x.out_of_range(plane_node, format!("{l} {r} {b} {t}"), requirement));
        }
        (gaze, vfov, shift, pixel_aspect)
    };

    let aperture = match x.child(node, "ApertureSize")? {
        Some(n) => {
            let a = x.scalar(n)?;
            if !(a >= 0.0) {
                return Err(x.out_of_range(n, a, ">= 0"));
            }
            if a > MAX_LENS_EXTENT {
                return Err(x.out_of_range(n, a, &lens_extent_requirement()));
            }
            a
        }
        None => 0.0,
    };
    let focus_distance = match optional_positive(x, node, "FocusDistance")? {
        None if aperture > 0.0 => return Err(x.missing(node, "FocusDistance")),
        Some(d) if d > MAX_LENS_EXTENT => {
            let node = x.required(node, "FocusDistance")?;
            return Err(x.out_of_range(node, d, &lens_extent_requirement()));
        }
        distance => distance,
    };
    let tonemap = x.child(node, "Tonemap")?.map(|t| tonemap(x, t)).transpose()?;
    let path_tracing = renderer(x, node, &mut notes)?;
    for note in &mut notes {
        *note = format!("camera '{image_name}': {note}");
    }
    Ok(CameraSpec {
        image_name,
        camera: CameraDesc {
            ortho_half_height: None,
            clip: (0.0, f64::INFINITY),
            mirrored: false,
            lookfrom: position,
            lookat: position + gaze,
            up,
            vfov_deg,
            width,
            height,
            aperture,
            focus_distance,
            lens_shape: if aperture > 0.0 { LensShape::Square } else { LensShape::Disk },
            shift,
            pixel_aspect,
        },
        spp,
        tonemap,
        path_tracing,
        notes,
    })
}

/// What a path-tracing camera's `<RendererParams>` change about the image it converges to.
/// ImportanceSampling only changes the noise (cosine instead of uniform directions), so it
/// is not kept: embray always samples the BSDF and, with MIS, the emitters.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct PathTracing {
    /// NextEventEstimation: lights are sampled explicitly. Without it a path reaches only
    /// what it can hit, so point and area lights (which no ray can hit) light nothing.
    pub next_event: bool,
    /// RussianRoulette: paths end by roulette alone, with no depth limit.
    pub roulette: bool,
}

/// `<Renderer>` and `<RendererParams>`: whether and how the camera path-traces.
fn renderer(
    x: &Xml,
    node: Node,
    notes: &mut Vec<String>,
) -> Result<Option<PathTracing>, SceneError> {
    let params = x.child(node, "RendererParams")?;
    let Some(renderer) = x.child(node, "Renderer")? else {
        if let Some(params) = params {
            return Err(x.error(params, "<RendererParams> without a <Renderer>"));
        }
        return Ok(None);
    };
    if x.text(renderer) != "PathTracing" {
        return Err(x.error(
            renderer,
            format!(
                "unsupported renderer \"{}\" (supported: PathTracing)",
                crate::excerpt::excerpt(x.text(renderer))
            ),
        ));
    }
    let mut mode = PathTracing { next_event: false, roulette: false };
    if let Some(params) = params {
        for (token, pos) in super::xml::tokens(params) {
            mode.next_event |= token == "NextEventEstimation";
            mode.roulette |= token == "RussianRoulette";
            if !["NextEventEstimation", "ImportanceSampling", "RussianRoulette"].contains(&token) {
                return Err(x.token_error(
                    params,
                    pos,
                    format!(
                        "unsupported renderer parameter \"{}\" (supported: NextEventEstimation, \
                         ImportanceSampling, RussianRoulette)",
                        crate::excerpt::excerpt(token)
                    ),
                ));
            }
        }
    }
    if !mode.next_event {
        notes.push(
            "without NextEventEstimation no path can reach a point or area light, so those \
             light nothing (as in the course's renderer); emissive objects still do"
                .to_owned(),
        );
    }
    Ok(Some(mode))
}

/// `<Tonemap>`: `<TMO>Photographic</TMO>`, `<TMOOptions>key burn-out-percent</TMOOptions>`,
/// `<Saturation>` and `<Gamma>` (each optional, defaulting to 0.18 1, 1 and 2.2).
fn tonemap(x: &Xml, node: Node) -> Result<Photographic, SceneError> {
    x.check_children(node, &["TMO", "TMOOptions", "Saturation", "Gamma"])?;
    let tmo = x.required(node, "TMO")?;
    if x.text(tmo) != "Photographic" {
        return Err(x.error(
            tmo,
            format!(
                "unsupported tone mapping operator \"{}\" (supported: Photographic)",
                crate::excerpt::excerpt(x.text(tmo))
            ),
        ));
    }
    let mut p = Photographic::default();
    if let Some(options) = x.child(node, "TMOOptions")? {
        let [key, burn_out] = x.numbers::<2>(options, false)?;
        (p.key, p.burn_out) = (key as f32, burn_out as f32);
    }
    if let Some(s) = x.child(node, "Saturation")? {
        p.saturation = x.scalar(s)? as f32;
    }
    if let Some(g) = x.child(node, "Gamma")? {
        p.gamma = x.scalar(g)? as f32;
    }
    if let Some(problem) = p.problem() {
        return Err(x.error(node, problem));
    }
    Ok(p)
}

/// The image window at distance `d`.
struct Window {
    l: f64,
    r: f64,
    b: f64,
    t: f64,
    d: f64,
}

impl Window {
    /// The vertical field of view (degrees), the lens shift and the pixel aspect that
    /// reproduce this window exactly, off-centre or not: a window whose aspect differs from
    /// the image's is stretched over it, as the course's pixel grid (r − l)/nx by
    /// (t − b)/ny does (galactica_static's square plane on a 16:9 image).
    fn projection(&self, (width, height): (u32, u32)) -> (f64, DVec2, f64) {
        let Window { l, r, b, t, d } = *self;
        let vfov = 2.0 * ((t - b) / (2.0 * d)).atan().to_degrees();
        let plane_aspect = (r - l) / (t - b);
        let image_aspect = width as f64 / height as f64;
        let pixel_aspect = if (plane_aspect - image_aspect).abs() > 1e-9 * image_aspect {
            plane_aspect / image_aspect
        } else {
            1.0
        };
        (vfov, DVec2::new((l + r) / (2.0 * d), (b + t) / (2.0 * d)), pixel_aspect)
    }
}

/// The positive number in `node`'s child `name`, if it has one.
fn optional_positive(x: &Xml, node: Node, name: &str) -> Result<Option<f64>, SceneError> {
    let Some(n) = x.child(node, name)? else { return Ok(None) };
    let value = x.scalar(n)?;
    if !(value > 0.0) {
        return Err(x.out_of_range(n, value, "> 0"));
    }
    Ok(Some(value))
}
