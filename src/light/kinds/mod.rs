//! The kinds of light a scene describes, one file each: its parameters (the scene model's
//! `LightDesc` lists them), how it reads them from any format's `Params` and writes them
//! back, how it moves with the scene, how far it reaches, and what it becomes in render
//! space. Adding a kind: a file here, a `mod` line and a line in `light_kinds!` below, and
//! a line in each reader whose format has it (the TOML reader needs none: it dispatches on
//! `type` by the kind's `NAME`).

mod ambient;
mod area;
mod directional;
mod environment;
mod point;
mod projector;
mod spot;

pub use ambient::Ambient;
pub use area::Area;
pub use directional::Directional;
pub use environment::{Environment, EnvironmentMap};
pub use point::Point;
pub use projector::{Projection, Projector};
pub use spot::{Spot, SpotCone, SpotProfile, SpotTexture};

use super::{DirectionalLight, Emitter, EnvironmentLight, PointLight};
use crate::params::{ParamError, ParamSink, Params, Resources};
use crate::texels::TextureImage;
use glam::{DAffine3, DVec3, Vec3};
use std::sync::Arc;

/// The render-space lights the kinds compile into, gathered before the light set is made.
#[derive(Default)]
pub struct LightParts {
    pub points: Vec<PointLight>,
    pub directional: Vec<DirectionalLight>,
    pub ambient: Vec3,
    /// Emitters without geometry (rays never hit them).
    pub invisible: Vec<Emitter>,
    pub environment: Option<EnvironmentLight>,
}

/// What every kind of light provides.
pub trait LightKind: Sized {
    /// Its `type` in the TOML format.
    const NAME: &'static str;
    /// How messages and `embray info` name one.
    const LABEL: &'static str;
    /// Every parameter it takes.
    const FIELDS: &'static [&'static str];
    /// Lit only through light sampling: no ray can hit it (a path tracer without next-event
    /// estimation never sees it).
    const ONLY_SAMPLED: bool = false;
    /// A scene takes at most one.
    const ONE_PER_SCENE: bool = false;

    fn read(params: &Params, resources: &dyn Resources) -> Result<Self, ParamError>;
    fn write(&self, out: &mut dyn ParamSink);
    /// Moves it with the scene (`--offset`).
    fn translate(&mut self, _offset: DVec3) {}
    /// How far from `origin` (largest coordinate difference) its light starts; 0 for light
    /// from infinitely far away.
    fn reach(&self, _origin: DVec3) -> f64 {
        0.0
    }
    fn compile(&self, render_from_world: &DAffine3, parts: &mut LightParts);
    /// The image it emits through, if any (for the memory estimate).
    fn image(&self) -> Option<&Arc<TextureImage>> {
        None
    }
    /// Its image gets a sampling table (a probability per texel).
    const SAMPLES_ITS_IMAGE: bool = false;
}

/// The largest coordinate difference between `p` and `origin` (NaN stays NaN).
pub(crate) fn distance(p: DVec3, origin: DVec3) -> f64 {
    if p.is_nan() { f64::NAN } else { (p - origin).abs().max_element() }
}

macro_rules! light_kinds {
    ($($variant:ident($kind:ty)),* $(,)?) => {
        /// A light of the scene model (world space, f64): one variant per kind.
        #[derive(Clone, Debug, PartialEq)]
        pub enum LightDesc {
            $($variant($kind)),*
        }

        impl LightDesc {
            /// Every kind's `NAME`.
            pub const NAMES: &'static [&'static str] = &[$(<$kind>::NAME),*];

            /// The label of the kind named `name`, if there is one.
            pub fn label_of(name: &str) -> Option<&'static str> {
                [$((<$kind>::NAME, <$kind>::LABEL)),*]
                    .into_iter()
                    .find_map(|(kind, label)| (kind == name).then_some(label))
            }

            /// The light of kind `name` from `params` (`None`: no such kind). Parameters
            /// the kind does not take are refused first; `type` is every kind's.
            pub fn read(
                name: &str,
                params: &Params,
                resources: &dyn Resources,
            ) -> Option<Result<Self, ParamError>> {
                $(if name == <$kind>::NAME {
                    let fields = [&["type"][..], <$kind>::FIELDS].concat();
                    return Some(params.check_fields(&fields).and_then(|()| {
                        <$kind>::read(params, resources).map(LightDesc::$variant)
                    }));
                })*
                None
            }

            pub fn name(&self) -> &'static str {
                match self { $(LightDesc::$variant(_) => <$kind>::NAME),* }
            }

            pub fn label(&self) -> &'static str {
                match self { $(LightDesc::$variant(_) => <$kind>::LABEL),* }
            }

            pub fn only_sampled(&self) -> bool {
                match self { $(LightDesc::$variant(_) => <$kind>::ONLY_SAMPLED),* }
            }

            pub fn one_per_scene(&self) -> bool {
                match self { $(LightDesc::$variant(_) => <$kind>::ONE_PER_SCENE),* }
            }

            /// Its `type` and parameters.
            pub fn write(&self, out: &mut dyn ParamSink) {
                out.text("type", self.name());
                match self { $(LightDesc::$variant(light) => light.write(out)),* }
            }

            pub fn translate(&mut self, offset: DVec3) {
                match self { $(LightDesc::$variant(light) => light.translate(offset)),* }
            }

            pub fn reach(&self, origin: DVec3) -> f64 {
                match self { $(LightDesc::$variant(light) => light.reach(origin)),* }
            }

            /// The image it emits through, and whether it gets a sampling table.
            pub fn image(&self) -> Option<(&Arc<TextureImage>, bool)> {
                match self {
                    $(LightDesc::$variant(light) => {
                        light.image().map(|i| (i, <$kind>::SAMPLES_ITS_IMAGE))
                    }),*
                }
            }

            pub fn compile(&self, render_from_world: &DAffine3, parts: &mut LightParts) {
                match self {
                    $(LightDesc::$variant(light) => light.compile(render_from_world, parts)),*
                }
            }
        }
    };
}

light_kinds! {
    Point(Point),
    Spot(Spot),
    Projector(Projector),
    Directional(Directional),
    Ambient(Ambient),
    Area(Area),
    Environment(Environment),
}
