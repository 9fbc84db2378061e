//! Names of the materials in the solver files.

use crate::scene::Scene;

/// The name of the matrix material: `"matrix"`, or `"matrix_fill"` when a phase is
/// already called `matrix`.
pub fn matrix_name(scene: &Scene) -> &'static str {
    if scene.phases.iter().any(|p| p.name == "matrix") {
        "matrix_fill"
    } else {
        "matrix"
    }
}

/// An Abaqus name for `name`: upper case, every character but ASCII letters, digits
/// and `_` replaced by `_`, prefixed by `prefix` (Abaqus names start with a letter and
/// hold no spaces).
pub fn section_name(prefix: &str, name: &str) -> String {
    let body: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '_' {
                c.to_ascii_uppercase()
            } else {
                '_'
            }
        })
        .collect();
    format!("{prefix}{body}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn section_names_are_abaqus_names() {
        assert_eq!(section_name("PHASE_", "α-ferrite 2"), "PHASE___FERRITE_2");
        assert_eq!(section_name("PHASE_", "needles"), "PHASE_NEEDLES");
    }
}
