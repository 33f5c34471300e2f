//! Command-line parsers for the library's named choices (`embray::choice::Choice`): clap
//! lists and checks the names, the library turns a name into its value.

use clap::builder::{PossibleValuesParser, TypedValueParser};
use embray::choice::Choice;
use embray::output::ToneMap;
use embray::scene::IntegratorKind;

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
    /// The curve for a scene rendered with `integrator`.
    pub fn resolve(self, integrator: IntegratorKind) -> ToneMap {
        match self {
            TonemapArg::Auto => ToneMap::for_integrator(integrator),
            TonemapArg::Curve(curve) => curve,
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
