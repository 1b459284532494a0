//! `unilateral`: frictional unilateral contact of 2D structures under a growing load.
//!
//! A thin front end: `main` parses the arguments, `run` hands each command to its module in
//! [`commands`], and [`failure`] is the one place where what went wrong becomes an exit status
//! (0 an answer, 2 bad input, 1 internal failure).

use std::process::ExitCode;

use clap::Parser;

mod args;
mod commands;
mod failure;
mod output;

use args::{Cli, Command};
use failure::Failure;

fn main() -> ExitCode {
    large_blocks_mapped();
    // faer's own parallel kernels are asked for where their bits do not depend on the number
    // of threads (the engine's refactorisation); everything else of faer (the sparse
    // factorisations and solves of the finite elements) runs on one thread, so that a model
    // gives the same bits on every machine.
    faer::set_global_parallelism(faer::Par::Seq);
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        Err(e) => {
            // Usage errors are bad input (2); --help and --version are answers (0).
            let code = if e.use_stderr() { 2 } else { 0 };
            let _ = e.print();
            return ExitCode::from(code);
        }
    };
    // The whole run on a worker of the thread pool: the parallel passes of every pivot are
    // then split with the one other worker by work stealing. Called from outside the pool, each
    // of them put the main thread to sleep and woke it (two context switches a pass, three
    // threads on two cores): the 1000-bearing beam ran 10 % longer. The workers get the main
    // thread's stack size, so no input needs more stack here than it did there.
    let pool = rayon::ThreadPoolBuilder::new()
        .stack_size(MAIN_STACK)
        .thread_name(|i| format!("unilateral-{i}"))
        .build();
    let outcome = match pool {
        Ok(pool) => pool.install(|| run(cli)),
        Err(_) => run(cli),
    };
    match outcome {
        Ok(()) => ExitCode::SUCCESS,
        Err(failure) => {
            output::err_line(&failure.message());
            ExitCode::from(failure.exit_code())
        }
    }
}

/// glibc raises its threshold for serving a large block by a mapping of its own each time such
/// a block is freed; after that, the refactorisation's `k × k` buffers (tens of MB, taken and
/// freed every few hundred pivots) come from the worker thread's heap and fragment it (the zone
/// at m = 1000 peaked at 204 MB instead of 174 once the run moved onto the pool). A fixed
/// threshold keeps every block from 1 MiB up in its own mapping, returned when freed. Fixing it
/// also fixes the threshold above which a heap's free top is given back (128 KiB by default):
/// at 128 KiB the ParaView frames' buffers were given back and faulted in again for every
/// frame (12 000 `madvise` calls for the 1000-bearing beam's `--vtk`); 8 MiB keeps them.
#[cfg(all(target_os = "linux", target_env = "gnu"))]
fn large_blocks_mapped() {
    // SAFETY: `mallopt` sets parameters of the allocator; it is called first thing in `main`,
    // before any other thread exists or anything is allocated on another thread.
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, 1 << 20);
        libc::mallopt(libc::M_TRIM_THRESHOLD, 8 << 20);
    }
}

#[cfg(not(all(target_os = "linux", target_env = "gnu")))]
fn large_blocks_mapped() {}

/// The stack of each worker thread: that of a Linux main thread (8 MiB; a spawned thread's
/// default is 2 MiB).
const MAIN_STACK: usize = 8 << 20;

fn run(cli: Cli) -> Result<(), Failure> {
    match cli.command {
        Command::Solve(args) => commands::solve::run(args),
        Command::Tableau(args) => commands::tableau::run(args),
        Command::Lcp(args) => commands::lcp::run(args),
        Command::Example(args) => {
            commands::example::run(args.name.as_deref(), &args.to, args.force)
        }
        Command::Zone(args) => commands::zone::run(args),
    }
}
