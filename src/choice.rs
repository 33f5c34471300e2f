//! Named choices (render space, backend, build quality, tone curve, …): one name per value,
//! parsed and printed by the library, so the command line (and any other front end) only
//! lists the names.

/// A closed set of values, each with one name.
pub trait Choice: Sized + Copy + 'static {
    /// What a value is, for messages ("render space").
    const WHAT: &'static str;
    /// Every value, in the order they are listed to users.
    const ALL: &'static [Self];
    fn name(self) -> &'static str;

    /// The value named `text`.
    fn from_name(text: &str) -> Result<Self, UnknownChoice> {
        Self::ALL.iter().copied().find(|c| c.name() == text).ok_or_else(|| UnknownChoice {
            what: Self::WHAT,
            given: crate::excerpt::excerpt(text),
            expected: Self::ALL.iter().map(|c| c.name()).collect(),
        })
    }
}

/// A name that is none of a [`Choice`]'s values.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("'{given}' is not a {what} (expected one of: {})", expected.join(", "))]
pub struct UnknownChoice {
    pub what: &'static str,
    /// The given text, cut to a short excerpt.
    pub given: String,
    pub expected: Vec<&'static str>,
}

/// Implements [`Choice`], `FromStr` and `Display` for an enum from its variants' names:
/// `named_choices!(RenderSpace, "render space", { Cameraworld => "cameraworld", .. })`.
macro_rules! named_choices {
    ($ty:ident, $what:literal, { $($variant:ident => $name:literal),+ $(,)? }) => {
        impl $crate::choice::Choice for $ty {
            const WHAT: &'static str = $what;
            const ALL: &'static [Self] = &[$($ty::$variant),+];
            fn name(self) -> &'static str {
                match self {
                    $($ty::$variant => $name),+
                }
            }
        }
        impl std::str::FromStr for $ty {
            type Err = $crate::choice::UnknownChoice;
            fn from_str(text: &str) -> Result<Self, Self::Err> {
                <$ty as $crate::choice::Choice>::from_name(text)
            }
        }
        impl std::fmt::Display for $ty {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str($crate::choice::Choice::name(*self))
            }
        }
    };
}
pub(crate) use named_choices;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render_space::RenderSpace;

    #[test]
    fn every_name_parses_back_to_its_value_and_others_are_refused() {
        for &space in RenderSpace::ALL {
            assert_eq!(space.to_string().parse::<RenderSpace>(), Ok(space));
        }
        let error = "sideways".parse::<RenderSpace>().unwrap_err();
        assert_eq!(
            error.to_string(),
            "'sideways' is not a render space (expected one of: cameraworld, camera, world)"
        );
    }
}
