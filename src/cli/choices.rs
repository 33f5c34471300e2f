//! Command-line parsers for the library's named choices (`embray::choice::Choice`): clap
//! lists and checks the names, the library turns a name into its value.

use clap::builder::{PossibleValuesParser, TypedValueParser};
use embray::choice::Choice;
use embray::output::ToneMap;
use embray::scene::RenderSettings;

/// A clap parser accepting exactly the names of `C`'s values.
pub fn choice<C: Choice + Clone + Send + Sync>() -> impl TypedValueParser<Value = C> {
    PossibleValuesParser::new(C::ALL.iter().map(|c| c.name())).try_map(|name| C::from_name(&name))
}

/// `--tonemap`: a curve, or `auto` (the scene's integrator decides).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum TonemapArg {
    #[default]
    Auto,
    Curve(ToneMap),
}

impl TonemapArg {
    /// The curve for a scene with `settings`: under `auto`, the photographic operator if
    /// the scene asks for it (a CENG795 camera's `<Tonemap>`), else its integrator's curve.
    pub fn resolve(self, settings: &RenderSettings) -> ToneMap {
        match self {
            TonemapArg::Auto if settings.tonemap.is_some() => ToneMap::Photographic,
            TonemapArg::Auto => settings.integrator.default_tone_map(),
            TonemapArg::Curve(curve) => curve,
        }
    }
}

/// How a PNG is made from the linear image, beyond the curve: the photographic operator's
/// parameters, a grading LUT and an exposure (`render` and `tonemap` share them).
#[derive(clap::Args, Debug, Clone, Default)]
pub struct LookArgs {
    #[command(flatten)]
    pub photographic: PhotographicArgs,
    /// A 3-D LUT (.cube, Adobe/Resolve format) applied to the PNG last, as a grading look.
    #[arg(long, value_name = "FILE.cube")]
    pub lut: Option<std::path::PathBuf>,
    /// Exposure adjustment in stops, applied before tone mapping (the PNG only).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub exposure: f32,
}

impl LookArgs {
    /// Refuses an exposure that is not a number or beyond what f32 can scale by.
    pub fn check(&self) -> anyhow::Result<()> {
        if !embray::output::exposure_in_range(self.exposure) {
            anyhow::bail!(
                "--exposure is {}, but must be a number of stops in [-{max}, {max}]",
                embray::params::show_large(self.exposure),
                max = embray::output::MAX_EXPOSURE_STOPS
            );
        }
        Ok(())
    }
}

/// The photographic operator's parameters on the command line; each overrides the scene's
/// (a CENG795 `<Tonemap>`) or the default.
#[derive(clap::Args, Debug, Clone, Default)]
pub struct PhotographicArgs {
    /// Photographic tone mapping: the key (the display value of the log-average luminance)
    /// [default: the scene's, else 0.18].
    #[arg(long)]
    pub key: Option<f32>,
    /// Photographic tone mapping: the percentage of pixels allowed to burn out to white
    /// (0: none) [default: the scene's, else 1].
    #[arg(long)]
    pub burn_out: Option<f32>,
    /// Photographic tone mapping: the colour saturation exponent (1 keeps colours, 0 is grey)
    /// [default: the scene's, else 1].
    #[arg(long)]
    pub saturation: Option<f32>,
    /// Photographic tone mapping: the display gamma [default: the scene's, else 2.2].
    #[arg(long)]
    pub gamma: Option<f32>,
}

impl PhotographicArgs {
    /// `scene`'s parameters (or the defaults) with the flags given applied, checked.
    /// The first photographic parameter given on the command line, for refusing it under
    /// another curve (where it would change nothing).
    pub fn first_given(&self) -> Option<&'static str> {
        [
            ("--key", self.key.is_some()),
            ("--burn-out", self.burn_out.is_some()),
            ("--saturation", self.saturation.is_some()),
            ("--gamma", self.gamma.is_some()),
        ]
        .into_iter()
        .find_map(|(flag, given)| given.then_some(flag))
    }

    /// Refuses photographic parameters under a curve that is not the photographic one.
    pub fn check_curve(&self, curve: embray::output::ToneMap) -> anyhow::Result<()> {
        match self.first_given() {
            Some(flag) if curve != embray::output::ToneMap::Photographic => anyhow::bail!(
                "{flag} sets the photographic operator, but the PNG's curve is {curve} (give \
                 --tonemap photographic, or leave {flag} out)"
            ),
            _ => Ok(()),
        }
    }

    pub fn resolve(
        &self,
        scene: Option<&embray::output::Photographic>,
    ) -> anyhow::Result<embray::output::Photographic> {
        let mut p = scene.copied().unwrap_or_default();
        p.key = self.key.unwrap_or(p.key);
        p.burn_out = self.burn_out.unwrap_or(p.burn_out);
        p.saturation = self.saturation.unwrap_or(p.saturation);
        p.gamma = self.gamma.unwrap_or(p.gamma);
        match p.problem() {
            Some(problem) => anyhow::bail!("photographic tone mapping: {problem}"),
            None => Ok(p),
        }
    }
}

/// Parses `auto` or a tone curve's name.
pub fn tonemap() -> impl TypedValueParser<Value = TonemapArg> {
    let names = std::iter::once("auto").chain(ToneMap::ALL.iter().map(|c| c.name()));
    PossibleValuesParser::new(names).try_map(|name| match name.as_str() {
        "auto" => Ok(TonemapArg::Auto),
        curve => ToneMap::from_name(curve).map(TonemapArg::Curve),
    })
}
