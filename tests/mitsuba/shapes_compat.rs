//! Mitsuba's shapes as Mitsuba builds them: texture coordinates, sides and transforms.
#![allow(unused_imports)]

use super::load_mitsuba;
