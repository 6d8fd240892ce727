//! Which circuits are lights, for the question only a person outside can answer: "Is
//! it lit?". The unit measures a lamp's current; only someone looking can
//! say the lamp shines, and the two together catch a lamp out on a pin that still
//! draws, or a lamp lit from another pin.
//!
//! Decision (what a light is called is known, how to match it is not): a name is split into words
//! at anything not a letter or digit and where a lower-case letter meets a capital
//! ("NavLts" is "Nav", "Lts"). It is a light when
//! - a word is "lt" or "lts" (whole words only: "Alt Field", "Main Alt" and "Volts"
//!   are not lights), or
//! - a word begins with "light", "strobe", "beacon", "nav", "landing" or "taxi"
//!   ("Lights", "Strobes", "Navigation", "Taxi/Ldg"; not "Flight Dir", since "light"
//!   must begin the word),
//!
//! unless a word names a radio or the gear ("com", "navcom", "radio", "gps", "vor",
//! "ils", "gear"): "Nav/Com 1" and "Landing Gear" are not lights.

/// Whether the circuit named `name` is a light (see the module's docs).
pub fn is_light(name: &str) -> bool {
    let words = words(name);
    let not_lights = ["com", "navcom", "radio", "gps", "vor", "ils", "gear"];
    if words.iter().any(|w| not_lights.contains(&w.as_str())) {
        return false;
    }
    let starts = ["light", "strobe", "beacon", "nav", "landing", "taxi"];
    words
        .iter()
        .any(|w| w == "lt" || w == "lts" || starts.iter().any(|s| w.starts_with(s)))
}

/// The name's words, lower-cased.
fn words(name: &str) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    let mut word = String::new();
    let mut prev_lower = false;
    for c in name.chars() {
        if !c.is_alphanumeric() {
            if !word.is_empty() {
                out.push(std::mem::take(&mut word));
            }
            prev_lower = false;
            continue;
        }
        if c.is_uppercase() && prev_lower && !word.is_empty() {
            out.push(std::mem::take(&mut word));
        }
        prev_lower = c.is_lowercase();
        word.extend(c.to_lowercase());
    }
    if !word.is_empty() {
        out.push(word);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lights_are_told_by_their_words() {
        for yes in [
            "Nav Lts",
            "Landing Lt",
            "Strobe",
            "Beacon",
            "Taxi",
            "NAV LTS",
            "LDG LT",
            "Panel Lt",
            "NavLts",
            "Strobes",
            "Landing/Taxi",
            "Cabin Lights",
            "Navigation",
            "Wig-wag Lt",
        ] {
            assert!(is_light(yes), "{yes} is a light");
        }
        for no in [
            "Alt Field",
            "Main Alt",
            "ALT FLD",
            "Volts",
            "Flight Dir",
            "EFIS",
            "Pitot Heat",
            "Boost Pump",
            "Nav/Com 1",
            "NAVCOM",
            "GPS Nav",
            "Landing Gear",
            "Starter",
            "",
        ] {
            assert!(!is_light(no), "{no} is not a light");
        }
    }
}
