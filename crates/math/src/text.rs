//! User text and numbers quoted in error messages, kept to what a one-line message can hold:
//! a 100,000-digit number or a multi-kilobyte reply is cut, an ellipsis marking the cut.

use std::borrow::Cow;

/// Characters of a value an error message echoes ([`value`], [`number`]).
pub const SHOWN_CHARS: usize = 40;

/// `text` cut to `limit` characters, an ellipsis marking the cut (trailing white space
/// dropped first).
#[must_use]
pub fn shorten(text: &str, limit: usize) -> Cow<'_, str> {
    let text = text.trim_end();
    match text.char_indices().nth(limit) {
        Some((at, _)) => Cow::Owned(format!("{}…", &text[..at])),
        None => Cow::Borrowed(text),
    }
}

/// A value as an error message echoes it: at most [`SHOWN_CHARS`] characters, a longer one
/// as its beginning and its end around an ellipsis (the end of a path is its file's name).
#[must_use]
pub fn value(text: &str) -> Cow<'_, str> {
    let count = text.chars().count();
    if count <= SHOWN_CHARS {
        return Cow::Borrowed(text);
    }
    let tail = SHOWN_CHARS * 2 / 5;
    let head: String = text.chars().take(SHOWN_CHARS - tail).collect();
    let end: String = text.chars().skip(count - tail).collect();
    Cow::Owned(format!("{head}…{end}"))
}

/// A number as an error message shows it: as Rust writes it (`1.5`, `-0.001`), or in
/// exponent form when that is longer than [`SHOWN_CHARS`] (`1e300`, not 301 digits).
#[must_use]
pub fn number(v: f64) -> String {
    let plain = v.to_string();
    if plain.len() > SHOWN_CHARS {
        format!("{v:e}")
    } else {
        plain
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_text_is_cut_with_an_ellipsis() {
        assert_eq!(shorten("abcdef", 3), "abc…");
        assert_eq!(shorten("abc  \n", 3), "abc");
        assert_eq!(shorten("αβγδ", 2), "αβ…");
        let digits = "9".repeat(100_000);
        let shown = value(&digits);
        assert_eq!(shown.chars().count(), SHOWN_CHARS + 1);
        assert_eq!(shown.find('…'), Some(24));
        let path = format!("\"/{}/thrust/t010.eng\"", "folder/".repeat(20));
        let shown = value(&path);
        assert!(shown.ends_with("thrust/t010.eng\""), "{shown}");
        assert_eq!(value("short"), "short");
    }

    #[test]
    fn huge_numbers_are_shown_in_exponent_form() {
        assert_eq!(number(1.5), "1.5");
        assert_eq!(number(-0.001), "-0.001");
        assert_eq!(number(1e300), "1e300");
        assert_eq!(number(-2.5e-320), "-2.5e-320");
        assert_eq!(number(f64::NAN), "NaN");
    }
}
