//! TOML values as text: floats that round-trip, vectors, strings, affine matrices.

use glam::{DAffine3, DVec3, Vec3};

/// A TOML float: `Debug` always writes a decimal point or an exponent, and round-trips.
pub(super) fn f(v: f64) -> String {
    format!("{v:?}")
}

pub(super) fn v3(v: DVec3) -> String {
    format!("[{}, {}, {}]", f(v.x), f(v.y), f(v.z))
}

pub(super) fn c3(v: Vec3) -> String {
    format!("[{:?}, {:?}, {:?}]", v.x, v.y, v.z)
}

/// A TOML basic string.
pub(super) fn quoted(text: &str) -> String {
    let mut out = String::from("\"");
    for ch in text.chars() {
        match ch {
            '"' => out += "\\\"",
            '\\' => out += "\\\\",
            c if (c as u32) < 0x20 || c == '\u{7f}' => out += &format!("\\u{:04x}", c as u32),
            c => out.push(c),
        }
    }
    out + "\""
}

pub(super) fn matrix(m: &DAffine3) -> String {
    let rows: Vec<String> = (0..3)
        .map(|r| {
            let row = m.matrix3.row(r);
            format!("[{}, {}, {}, {}]", f(row.x), f(row.y), f(row.z), f(m.translation[r]))
        })
        .collect();
    format!("[{{ matrix = [{}, [0.0, 0.0, 0.0, 1.0]] }}]", rows.join(", "))
}

/// Parameters written as `key = value` lines.
pub(super) struct TomlLines<'a>(pub &'a mut String);

impl crate::params::ParamSink for TomlLines<'_> {
    fn text(&mut self, name: &str, value: &str) {
        *self.0 += &format!("{name} = {}\n", quoted(value));
    }

    fn number(&mut self, name: &str, value: f64) {
        *self.0 += &format!("{name} = {}\n", f(value));
    }

    fn vec3(&mut self, name: &str, value: DVec3) {
        *self.0 += &format!("{name} = {}\n", v3(value));
    }

    fn color(&mut self, name: &str, value: Vec3) {
        *self.0 += &format!("{name} = {}\n", c3(value));
    }

    fn numbers(&mut self, name: &str, values: &[f64]) {
        let list: Vec<String> = values.iter().map(|&v| f(v)).collect();
        *self.0 += &format!("{name} = [{}]\n", list.join(", "));
    }

    fn path(&mut self, name: &str, value: &std::path::Path) {
        let absolute = std::path::absolute(value).unwrap_or_else(|_| value.to_path_buf());
        self.text(name, &absolute.to_string_lossy());
    }
}
