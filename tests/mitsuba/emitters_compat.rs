//! Mitsuba's emitters, sensors and transforms read as Mitsuba reads them.
#![allow(unused_imports)]

use super::load_mitsuba;
