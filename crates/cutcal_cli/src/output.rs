//! Standard output of the CLI. A reader that closes the pipe early (`cutcal ... | head`) has taken
//! all it wants: the write ends quietly with success instead of a panic in `println!`, as
//! ripgrep and the coreutils behave.

use std::io::{ErrorKind, Write};

/// Writes `text` to standard output and flushes; a closed pipe is not an error.
///
/// # Errors
/// Any other write error of standard output.
pub fn emit(text: &str) -> std::io::Result<()> {
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        Err(e) if e.kind() == ErrorKind::BrokenPipe => Ok(()),
        r => r,
    }
}

/// [`emit`] with a trailing newline.
///
/// # Errors
/// As [`emit`].
pub fn emit_line(text: &str) -> std::io::Result<()> {
    emit(&format!("{text}\n"))
}
