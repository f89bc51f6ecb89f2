//! Ctrl-C: the first press asks the running solves to stop (each keeps its best design and the
//! command writes it, with status `interrupted`); the second exits at once.

use anyhow::{Context, Result};
use netspec::solvers::Interrupt;
use std::sync::atomic::{AtomicUsize, Ordering};

/// Exit code after an interrupt (128 + SIGINT, as shells report it).
pub const EXIT_INTERRUPTED: u8 = 130;

/// Installs the Ctrl-C handler and returns the interrupt it triggers.
pub fn install() -> Result<Interrupt> {
    let interrupt = Interrupt::new();
    let handle = interrupt.clone();
    let presses = AtomicUsize::new(0);
    ctrlc::set_handler(move || {
        if presses.fetch_add(1, Ordering::SeqCst) == 0 {
            eprintln!(
                "\ninterrupt: stopping the solver and keeping its best design (press Ctrl-C again to quit at once)"
            );
            handle.trigger();
        } else {
            eprintln!("\ninterrupt: quitting");
            std::process::exit(i32::from(EXIT_INTERRUPTED));
        }
    })
    .context("installing the Ctrl-C handler")?;
    Ok(interrupt)
}
