//! Progress on stderr: bars on long work (multistart batches, bootstrap, project lists, signal
//! files), drawn only when stderr is a terminal and `--quiet` is not given, so pipes, CI logs and
//! `--json` stay clean; and the project runner's stage lines (`[C38] rendering FE cards`), printed
//! unless `--quiet`.

use std::cell::RefCell;
use std::io::IsTerminal;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// Creates a bar of `len` steps labelled `message`; hidden when quiet or not on a terminal.
#[must_use]
pub fn bar(len: u64, message: &str, quiet: bool) -> ProgressBar {
    let pb = ProgressBar::with_draw_target(Some(len), draw_target(quiet));
    if let Ok(style) = ProgressStyle::with_template("{msg:>24} [{bar:30}] {pos}/{len} {elapsed}") {
        pb.set_style(style.progress_chars("=> "));
    }
    pb.set_message(message.to_string());
    pb
}

fn draw_target(quiet: bool) -> ProgressDrawTarget {
    if quiet || !std::io::stderr().is_terminal() {
        ProgressDrawTarget::hidden()
    } else {
        ProgressDrawTarget::stderr()
    }
}

/// The CLI's [`cutcal_report::Progress`]: stage lines on stderr and one bar per item batch.
#[derive(Debug)]
pub struct Terminal {
    quiet: bool,
    bar: RefCell<Option<ProgressBar>>,
}

impl Terminal {
    /// Progress on stderr, or none with `quiet`.
    #[must_use]
    pub fn new(quiet: bool) -> Self {
        Self { quiet, bar: RefCell::new(None) }
    }

    /// Clears the current bar.
    pub fn finish(&self) {
        if let Some(b) = self.bar.borrow_mut().take() {
            b.finish_and_clear();
        }
    }
}

impl cutcal_report::Progress for Terminal {
    fn stage(&self, material: &str, message: &str) {
        if !self.quiet {
            #[allow(clippy::print_stderr)] // progress goes to stderr, results to files/stdout
            {
                eprintln!("[{material}] {message}");
            }
        }
    }

    fn items(&self, what: &str, done: usize, total: usize) {
        let mut slot = self.bar.borrow_mut();
        let b = slot.get_or_insert_with(|| bar(total as u64, what, self.quiet));
        b.set_position(done as u64);
        if done >= total {
            b.finish_and_clear();
            *slot = None;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quiet_bar_is_hidden() {
        assert!(bar(10, "x", true).is_hidden());
    }
}
