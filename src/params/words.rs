//! A message's parameters in a front end's words: the library writes a parameter as its
//! marker (`⟨mesh_angle⟩`, the [`Spec`]'s `Display`); the command line shows it as its flag
//! (`--mesh-angle`), Python as its keyword (`mesh_angle`), a command with flags of its own
//! (coverage's `--margins`) through its own map.

use super::{by_name, Spec, CLOSE, OPEN};

/// `text` with every marker replaced by `word` of its parameter; a marker of no known
/// parameter shows its bare name.
pub fn render(text: &str, word: &dyn Fn(&'static Spec) -> String) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(at) = rest.find(OPEN) {
        let after = &rest[at + OPEN.len_utf8()..];
        let Some(end) = after.find(CLOSE) else {
            break;
        };
        out.push_str(&rest[..at]);
        let name = &after[..end];
        match by_name(name) {
            Some(spec) => out.push_str(&word(spec)),
            None => out.push_str(name),
        }
        rest = &after[end + CLOSE.len_utf8()..];
    }
    out.push_str(rest);
    out
}

/// `text` in the command line's words: each parameter as its flag.
pub fn flags(text: &str) -> String {
    render(text, &|s| s.flag.to_string())
}

/// `text` in Python's words: each parameter as its keyword.
pub fn keywords(text: &str) -> String {
    render(text, &|s| s.name.to_string())
}

/// The parameters `text` names, in order, each once.
pub fn named(text: &str) -> Vec<&'static Spec> {
    let found = std::cell::RefCell::new(Vec::<&'static Spec>::new());
    render(text, &|s| {
        let mut found = found.borrow_mut();
        if !found.iter().any(|f| std::ptr::eq(*f, s)) {
            found.push(s);
        }
        String::new()
    });
    found.into_inner()
}
