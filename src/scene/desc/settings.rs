//! How the scene is rendered: integrator, samples, depth, tone curve.

use super::texture::TextureDesc;
use glam::Vec3;

/// Which light-transport algorithm renders the scene.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum IntegratorKind {
    /// Path tracing with next-event estimation and MIS.
    #[default]
    Path,
    /// The CENG795 course model: ambient + Blinn-Phong direct light with shadow rays,
    /// recursive mirror/conductor/dielectric, values in 0–255 units clamped.
    Whitted,
}

crate::choice::named_choices!(IntegratorKind, "integrator", {
    Path => "path",
    Whitted => "whitted",
});

impl IntegratorKind {
    /// The curve a scene gets unless one is asked for: the course's clamp for Whitted
    /// (CENG795) scenes, ACES otherwise.
    pub fn default_tone_map(self) -> crate::output::ToneMap {
        match self {
            IntegratorKind::Whitted => crate::output::ToneMap::Clamp255,
            IntegratorKind::Path => crate::output::ToneMap::Aces,
        }
    }
}

/// Defaults for the renderer that a scene may carry; command-line options override them.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderSettings {
    pub spp: u32,
    pub max_depth: u32,
    pub background: Vec3,
    /// Shadow rays towards area lights per shading point.
    pub light_samples: u32,
    pub integrator: IntegratorKind,
    /// The photographic tone mapping the scene asks for its PNG (a CENG795 camera's
    /// `<Tonemap>`); `None`: the integrator's default curve.
    pub tonemap: Option<crate::output::Photographic>,
    /// A picture behind the scene (the course's replace_background): camera rays that leave
    /// the scene see it stretched over the image (u across, v down from the top), in place
    /// of the background colour or the environment. Other rays that leave see those.
    pub background_texture: Option<TextureDesc>,
    /// How samples are weighted into pixels (the box: each pixel averages its own).
    pub filter: crate::sampling::filter::PixelFilter,
    /// What the filter does at the image's edges.
    pub filter_edges: crate::sampling::filter::FilterEdges,
    /// Camera rays do not see lights (emitters, the environment, the background): they
    /// only light the scene (Mitsuba's `hide_emitters`).
    pub hide_emitters: bool,
    /// Which normal decides the side of a surface that light arrives from or leaves to.
    pub sides: Sides,
    /// The AOVs the scene asks its EXR to carry (Mitsuba's `aov` integrator); `--aovs`
    /// overrides them, and without either the EXR carries depth and normal.
    pub aovs: Option<crate::output::Aovs>,
    /// The surface interaction, counted from 1 (as Mitsuba's `rr_depth` counts), from which
    /// Russian roulette may end a path: 4 unless a scene says otherwise (Mitsuba's scenes: 5).
    pub rr_depth: u32,
    /// The window of the image the scene asks for (Mitsuba's film crop); `--crop` overrides
    /// it and `--resolution` drops it (its pixels are the scene's).
    pub crop: Option<crate::film::Tile>,
    /// The seed of the render's random numbers (Mitsuba's sampler `seed`); `--seed`
    /// overrides it.
    pub seed: u64,
    /// Sample positions jittered within their pixel strata (Mitsuba's stratified samplers'
    /// `jitter`); false puts them at stratum centres, as `--no-jitter` does.
    pub jitter: bool,
}

/// Which normal decides the side of a surface a direction is on, where a smooth-shaded
/// mesh's shading normal leans away from its triangle's (near its silhouette).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Sides {
    /// The shading normal and the triangle must agree: light from below the triangle is
    /// not taken, and a scattered ray that would pass through it ends (no light leaks
    /// through the surface, at the cost of some light lost near silhouettes).
    #[default]
    Both,
    /// The shading normal alone, as Mitsuba 3 has it: a ray below the triangle but above
    /// the shading normal passes through the surface and counts.
    Shading,
}

/// Where Russian roulette starts unless a scene says.
pub const DEFAULT_RR_DEPTH: u32 = 4;

impl Default for RenderSettings {
    fn default() -> Self {
        RenderSettings {
            spp: 16,
            max_depth: 5,
            background: Vec3::ZERO,
            light_samples: 1,
            integrator: IntegratorKind::Path,
            tonemap: None,
            background_texture: None,
            filter: Default::default(),
            filter_edges: Default::default(),
            hide_emitters: false,
            sides: Sides::Both,
            aovs: None,
            rr_depth: DEFAULT_RR_DEPTH,
            crop: None,
            seed: 0,
            jitter: true,
        }
    }
}
