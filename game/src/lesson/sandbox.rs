//! The kernel's sandbox around a lesson's process (Linux): once the
//! interpreter has started and before the lesson's code runs, the process
//! drops, by allowlist, what a lesson never needs. The audit hook of
//! `lesson::watchdog` stays, for friendly messages; this is what holds
//! when a lesson walks past it (pure Python through `_posixsubprocess`, C
//! through `ctypes`).
//!
//! - **Files** (Landlock): the file system is read-only, and only where
//!   the interpreter and the lesson read (the Python installation and its
//!   `sys.path`, `/usr`, the lesson's own folder, a few files of `/etc`,
//!   `/dev` and `/proc/self`); the one place it may write is a private
//!   temporary folder (`TMPDIR`), made for it by the game and removed with
//!   it. A kernel without Landlock runs the lesson with a message saying
//!   its files are not restricted.
//! - **System calls** (seccomp-bpf): an allowlist of what Python, its
//!   threads and the game's host use; anything else fails with `EPERM`.
//!   Refused: creating a process (`fork`, `vfork`, `clone` without
//!   `CLONE_THREAD`; `clone3` says `ENOSYS`, so that threads are made
//!   with `clone`), `execve`/`execveat`, signals to any process but its
//!   own (`kill`, `tgkill`, `tkill`, `rt_sigqueueinfo`;
//!   `pidfd_open`/`pidfd_send_signal`), `ptrace` and `process_vm_*`,
//!   new sockets (`socket`, `connect`, `bind`, `listen`, `accept`; a
//!   `socketpair` of its own is allowed), `setsid`/`setpgid`, `prctl`
//!   but naming threads and memory, raising its own limits.
//! - **Limits**: address space (`--memory-limit`, set earlier, in
//!   [`super::child_process`]), [`CPU_LIMIT_S`] of CPU time,
//!   [`OPEN_FILES`] open files, [`FILE_SIZE`] per file written, no core
//!   dumps.
//!
//! The process runs in its own process group, which the game kills whole
//! when the lesson ends; with process creation refused nothing else is
//! in it.

use std::path::{Path, PathBuf};

/// CPU time a lesson's process may use, s (a school day: the window's
/// lesson runs as long as the class).
pub const CPU_LIMIT_S: u64 = 12 * 3600;

/// Most files a lesson's process may have open at once.
pub const OPEN_FILES: u64 = 256;

/// Largest file a lesson's process may write, bytes.
pub const FILE_SIZE: u64 = 256 << 20;

/// The environment variable that names the private temporary folder the
/// game made for the lesson's process (also its `TMPDIR`).
pub const SCRATCH_ENV: &str = "LIGHTCONE_LESSON_TMP";

/// A private temporary folder for one lesson's process, removed when
/// dropped (after the process ended).
pub(crate) struct Scratch(PathBuf);

impl Scratch {
    /// Makes a new folder, readable by its owner only.
    pub(crate) fn new() -> Result<Self, String> {
        use std::os::unix::fs::DirBuilderExt;
        static N: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
        let n = N.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let dir = std::env::temp_dir().join(format!("lightcone-lesson-{}-{n}", std::process::id()));
        std::fs::DirBuilder::new()
            .mode(0o700)
            .create(&dir)
            .map_err(|e| {
                format!(
                    "cannot make the lesson's temporary folder {}: {e}",
                    dir.display()
                )
            })?;
        Ok(Self(dir))
    }

    /// The folder.
    pub(crate) fn path(&self) -> &Path {
        &self.0
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// Where the interpreter reads: the prefixes of the Python installation
/// and every folder on `sys.path` (GIL taken here).
fn python_paths() -> Vec<PathBuf> {
    use pyo3::prelude::*;
    Python::attach(|py| -> PyResult<Vec<PathBuf>> {
        let sys = py.import("sys")?;
        let mut paths: Vec<String> = sys.getattr("path")?.extract().unwrap_or_default();
        for name in ["prefix", "base_prefix", "exec_prefix", "base_exec_prefix"] {
            if let Ok(p) = sys.getattr(name).and_then(|p| p.extract::<String>()) {
                paths.push(p);
            }
        }
        Ok(paths.into_iter().map(PathBuf::from).collect())
    })
    .unwrap_or_default()
}

/// Enters the sandbox; `lesson_dir` is the lesson's own folder (read
/// only). Call it once the interpreter has started, before the lesson's
/// code runs, with no other thread running yet (Landlock holds for the
/// calling thread and the threads it starts). Returns what could not be
/// set up on this kernel (each a sentence for stderr: the lesson runs
/// without it); fails only when a limit that was set up cannot be.
pub(crate) fn enter(lesson_dir: &Path) -> Result<Vec<String>, String> {
    let scratch = std::env::var_os(SCRATCH_ENV).map(PathBuf::from);
    let mut reads = python_paths();
    reads.push(lesson_dir.to_path_buf());
    // The shipped scenes (`world.load` of `assets/scenes/NAME.toml` from a
    // lesson anywhere), read-only like the lesson's own folder.
    let assets = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets");
    if let Ok(assets) = assets.canonicalize() {
        reads.push(assets);
    }
    imp::enter(&reads, scratch.as_deref())
}

#[cfg(not(target_os = "linux"))]
mod imp {
    use std::path::{Path, PathBuf};

    pub(super) fn enter(_: &[PathBuf], _: Option<&Path>) -> Result<Vec<String>, String> {
        Ok(vec![
            "this system has no Landlock and no seccomp: the lesson's process is not sandboxed \
             (only its own process group and memory limit hold)"
                .to_owned(),
        ])
    }
}

#[cfg(target_os = "linux")]
mod imp {
    use std::collections::BTreeMap;
    use std::path::{Path, PathBuf};

    use landlock::{
        ABI, Access, AccessFs, PathBeneath, PathFd, Ruleset, RulesetAttr, RulesetCreatedAttr,
        RulesetStatus,
    };
    use seccompiler::{
        SeccompAction, SeccompCmpArgLen as Len, SeccompCmpOp as Op, SeccompCondition as Cond,
        SeccompFilter, SeccompRule,
    };

    use super::{CPU_LIMIT_S, FILE_SIZE, OPEN_FILES};

    /// Files outside `sys.path` that the interpreter and its libraries
    /// read (the dynamic loader's cache for `ctypes` and extension
    /// modules, the time zone, devices Python opens, the CPU count).
    const SYSTEM_READS: [&str; 12] = [
        "/usr",
        "/lib",
        "/lib64",
        "/etc/ld.so.cache",
        "/etc/localtime",
        "/etc/nsswitch.conf",
        "/dev/null",
        "/dev/zero",
        "/dev/urandom",
        "/dev/random",
        "/proc/self",
        "/sys/devices/system/cpu",
    ];

    pub(super) fn enter(reads: &[PathBuf], scratch: Option<&Path>) -> Result<Vec<String>, String> {
        let mut missing = Vec::new();
        limits()?;
        if let Some(why) = files(reads, scratch) {
            missing.push(why);
        }
        if let Some(why) = syscalls() {
            missing.push(why);
        }
        Ok(missing)
    }

    /// CPU time, open files, file size and core dumps.
    fn limits() -> Result<(), String> {
        for (resource, value, name) in [
            (libc::RLIMIT_CPU, CPU_LIMIT_S, "CPU time"),
            (libc::RLIMIT_NOFILE, OPEN_FILES, "open files"),
            (libc::RLIMIT_FSIZE, FILE_SIZE, "file size"),
            (libc::RLIMIT_CORE, 0, "core dumps"),
        ] {
            let limit = libc::rlimit {
                rlim_cur: value,
                rlim_max: value,
            };
            // SAFETY: a plain system call on this process's own limits.
            if unsafe { libc::setrlimit(resource, &limit) } != 0 {
                return Err(format!(
                    "cannot limit the lesson's {name}: {}",
                    std::io::Error::last_os_error()
                ));
            }
        }
        Ok(())
    }

    /// Landlock: read-only where the interpreter and the lesson read,
    /// read-write in `scratch` only. `Some(why)` where the kernel cannot.
    fn files(reads: &[PathBuf], scratch: Option<&Path>) -> Option<String> {
        let abi = ABI::V5;
        let read = AccessFs::from_read(abi);
        let all = AccessFs::from_all(abi);
        let built = (|| -> Result<RulesetStatus, landlock::RulesetError> {
            let mut ruleset = Ruleset::default().handle_access(all)?.create()?;
            let system = SYSTEM_READS.iter().map(PathBuf::from);
            for path in reads.iter().cloned().chain(system) {
                // What does not exist here is not needed.
                if let Ok(fd) = PathFd::new(&path) {
                    ruleset = ruleset.add_rule(PathBeneath::new(fd, read))?;
                }
            }
            if let Some(fd) = scratch.and_then(|s| PathFd::new(s).ok()) {
                ruleset = ruleset.add_rule(PathBeneath::new(fd, all))?;
            }
            Ok(ruleset.restrict_self()?.ruleset)
        })();
        match built {
            Ok(RulesetStatus::FullyEnforced | RulesetStatus::PartiallyEnforced) => None,
            Ok(RulesetStatus::NotEnforced) => Some(
                "this kernel has no Landlock: the lesson's files are not restricted \
                 (its system calls and limits still are)"
                    .to_owned(),
            ),
            Err(e) => Some(format!(
                "Landlock could not be set up ({e}): the lesson's files are not restricted"
            )),
        }
    }

    /// A condition: argument `arg` (64 bits) `op` `value`.
    fn cond(arg: u8, op: Op, value: u64) -> Cond {
        Cond::new(arg, Len::Qword, op, value).unwrap_or_else(|_| unreachable!("argument < 6"))
    }

    /// A rule of one condition.
    fn rule(arg: u8, op: Op, value: u64) -> Vec<SeccompRule> {
        vec![SeccompRule::new(vec![cond(arg, op, value)]).unwrap_or_else(|_| unreachable!())]
    }

    /// A rule that holds when argument `arg` is one of `values`.
    fn one_of(arg: u8, values: &[u64]) -> Vec<SeccompRule> {
        values
            .iter()
            .map(|v| {
                SeccompRule::new(vec![cond(arg, Op::Eq, *v)]).unwrap_or_else(|_| unreachable!())
            })
            .collect()
    }

    /// System calls allowed whatever their arguments.
    const ALLOWED: &[libc::c_long] = &[
        libc::SYS_read,
        libc::SYS_write,
        libc::SYS_readv,
        libc::SYS_writev,
        libc::SYS_pread64,
        libc::SYS_pwrite64,
        libc::SYS_preadv,
        libc::SYS_pwritev,
        libc::SYS_preadv2,
        libc::SYS_pwritev2,
        libc::SYS_openat,
        libc::SYS_close,
        libc::SYS_close_range,
        libc::SYS_fstat,
        libc::SYS_newfstatat,
        libc::SYS_statx,
        libc::SYS_statfs,
        libc::SYS_fstatfs,
        libc::SYS_lseek,
        libc::SYS_mmap,
        libc::SYS_munmap,
        libc::SYS_mprotect,
        libc::SYS_madvise,
        libc::SYS_mremap,
        libc::SYS_msync,
        libc::SYS_mincore,
        libc::SYS_brk,
        libc::SYS_rt_sigaction,
        libc::SYS_rt_sigprocmask,
        libc::SYS_rt_sigreturn,
        libc::SYS_rt_sigpending,
        libc::SYS_rt_sigtimedwait,
        libc::SYS_rt_sigsuspend,
        libc::SYS_sigaltstack,
        libc::SYS_ioctl,
        libc::SYS_fcntl,
        libc::SYS_flock,
        libc::SYS_fsync,
        libc::SYS_fdatasync,
        libc::SYS_ftruncate,
        libc::SYS_fallocate,
        libc::SYS_fadvise64,
        libc::SYS_getdents64,
        libc::SYS_getcwd,
        libc::SYS_chdir,
        libc::SYS_fchdir,
        libc::SYS_renameat,
        libc::SYS_renameat2,
        libc::SYS_mkdirat,
        libc::SYS_unlinkat,
        libc::SYS_readlinkat,
        libc::SYS_faccessat,
        libc::SYS_faccessat2,
        libc::SYS_fchmod,
        libc::SYS_fchmodat,
        libc::SYS_utimensat,
        libc::SYS_umask,
        libc::SYS_dup,
        libc::SYS_dup3,
        libc::SYS_pipe2,
        libc::SYS_getrandom,
        libc::SYS_eventfd2,
        libc::SYS_epoll_create1,
        libc::SYS_epoll_ctl,
        libc::SYS_epoll_pwait,
        libc::SYS_ppoll,
        libc::SYS_pselect6,
        libc::SYS_gettimeofday,
        libc::SYS_clock_gettime,
        libc::SYS_clock_getres,
        libc::SYS_clock_nanosleep,
        libc::SYS_nanosleep,
        libc::SYS_getitimer,
        libc::SYS_setitimer,
        libc::SYS_times,
        libc::SYS_getrusage,
        libc::SYS_sysinfo,
        libc::SYS_uname,
        libc::SYS_getuid,
        libc::SYS_geteuid,
        libc::SYS_getgid,
        libc::SYS_getegid,
        libc::SYS_getresuid,
        libc::SYS_getresgid,
        libc::SYS_getgroups,
        libc::SYS_getpid,
        libc::SYS_getppid,
        libc::SYS_gettid,
        libc::SYS_getpgid,
        libc::SYS_getsid,
        libc::SYS_getpriority,
        libc::SYS_sched_yield,
        libc::SYS_sched_getaffinity,
        libc::SYS_sched_getparam,
        libc::SYS_sched_getscheduler,
        libc::SYS_sched_get_priority_max,
        libc::SYS_sched_get_priority_min,
        libc::SYS_futex,
        libc::SYS_set_robust_list,
        libc::SYS_get_robust_list,
        libc::SYS_rseq,
        libc::SYS_set_tid_address,
        libc::SYS_membarrier,
        libc::SYS_get_mempolicy,
        libc::SYS_exit,
        libc::SYS_exit_group,
        libc::SYS_restart_syscall,
        // Only ever adds filters (the second is installed through it).
        libc::SYS_seccomp,
        // On sockets it already holds (a `socketpair` of its own).
        libc::SYS_socketpair,
        libc::SYS_sendmsg,
        libc::SYS_recvmsg,
        libc::SYS_sendto,
        libc::SYS_recvfrom,
        libc::SYS_shutdown,
        libc::SYS_getsockopt,
        libc::SYS_setsockopt,
        libc::SYS_getsockname,
        libc::SYS_getpeername,
        #[cfg(target_arch = "x86_64")]
        libc::SYS_open,
        #[cfg(target_arch = "x86_64")]
        libc::SYS_stat,
        #[cfg(target_arch = "x86_64")]
        libc::SYS_lstat,
        #[cfg(target_arch = "x86_64")]
        libc::SYS_access,
        #[cfg(target_arch = "x86_64")]
        libc::SYS_readlink,
        #[cfg(target_arch = "x86_64")]
        libc::SYS_pipe,
        #[cfg(target_arch = "x86_64")]
        libc::SYS_dup2,
        #[cfg(target_arch = "x86_64")]
        libc::SYS_poll,
        #[cfg(target_arch = "x86_64")]
        libc::SYS_select,
        #[cfg(target_arch = "x86_64")]
        libc::SYS_epoll_wait,
        #[cfg(target_arch = "x86_64")]
        libc::SYS_epoll_create,
        #[cfg(target_arch = "x86_64")]
        libc::SYS_rename,
        #[cfg(target_arch = "x86_64")]
        libc::SYS_mkdir,
        #[cfg(target_arch = "x86_64")]
        libc::SYS_rmdir,
        #[cfg(target_arch = "x86_64")]
        libc::SYS_unlink,
        #[cfg(target_arch = "x86_64")]
        libc::SYS_chmod,
        #[cfg(target_arch = "x86_64")]
        libc::SYS_getdents,
        #[cfg(target_arch = "x86_64")]
        libc::SYS_time,
        #[cfg(target_arch = "x86_64")]
        libc::SYS_arch_prctl,
        #[cfg(target_arch = "x86_64")]
        libc::SYS_getrlimit,
        #[cfg(target_arch = "x86_64")]
        libc::SYS_alarm,
        #[cfg(target_arch = "x86_64")]
        libc::SYS_pause,
        #[cfg(target_arch = "x86_64")]
        libc::SYS_getpgrp,
    ];

    /// The allowlist: each allowed call, with the conditions on its
    /// arguments where it has some.
    fn allowlist() -> BTreeMap<i64, Vec<SeccompRule>> {
        // SAFETY: a plain system call without arguments.
        let me = unsafe { libc::getpid() } as u64;
        let mut rules: BTreeMap<i64, Vec<SeccompRule>> =
            ALLOWED.iter().map(|&call| (call, vec![])).collect();
        // Threads only: a clone without CLONE_THREAD is a new process.
        let thread = libc::CLONE_THREAD as u64;
        rules.insert(libc::SYS_clone, rule(0, Op::MaskedEq(thread), thread));
        // Signals to its own process only (its watchdog signals the hook's
        // thread; Python's `os.kill(os.getpid(), …)`).
        for call in [
            libc::SYS_kill,
            libc::SYS_tgkill,
            libc::SYS_rt_sigqueueinfo,
            libc::SYS_rt_tgsigqueueinfo,
        ] {
            rules.insert(call, rule(0, Op::Eq, me));
        }
        // Its own limits, read (a new limit, even lower, is refused: as
        // root it could raise them).
        rules.insert(
            libc::SYS_prlimit64,
            vec![
                SeccompRule::new(vec![cond(0, Op::Eq, 0), cond(2, Op::Eq, 0)])
                    .unwrap_or_else(|_| unreachable!()),
                SeccompRule::new(vec![cond(0, Op::Eq, me), cond(2, Op::Eq, 0)])
                    .unwrap_or_else(|_| unreachable!()),
            ],
        );
        // Naming its threads and memory, and reading flags; no other prctl.
        const PR_SET_VMA: u64 = 0x5356_4d41;
        rules.insert(
            libc::SYS_prctl,
            one_of(
                0,
                &[
                    libc::PR_SET_NAME as u64,
                    libc::PR_GET_NAME as u64,
                    PR_SET_VMA,
                    libc::PR_GET_DUMPABLE as u64,
                    libc::PR_CAPBSET_READ as u64,
                    libc::PR_GET_NO_NEW_PRIVS as u64,
                    // Only ever restricts (the second filter sets it).
                    libc::PR_SET_NO_NEW_PRIVS as u64,
                    libc::PR_GET_SECCOMP as u64,
                ],
            ),
        );
        // Its own threads' affinity (OpenBLAS pins its threads).
        rules.insert(libc::SYS_sched_setaffinity, rule(0, Op::Eq, 0));
        rules
    }

    /// seccomp-bpf: the allowlist (anything else fails with `EPERM`),
    /// then `clone3` answered `ENOSYS` (the C library then makes threads
    /// with `clone`, whose flags the first filter can read). `Some(why)`
    /// where the kernel cannot.
    fn syscalls() -> Option<String> {
        let arch = match seccompiler::TargetArch::try_from(std::env::consts::ARCH) {
            Ok(a) => a,
            Err(_) => {
                return Some(format!(
                    "no seccomp filter for {}: the lesson's system calls are not restricted",
                    std::env::consts::ARCH
                ));
            }
        };
        let eperm = SeccompAction::Errno(libc::EPERM as u32);
        let filters = [
            SeccompFilter::new(allowlist(), eperm, SeccompAction::Allow, arch),
            SeccompFilter::new(
                BTreeMap::from([(libc::SYS_clone3, vec![])]),
                SeccompAction::Allow,
                SeccompAction::Errno(libc::ENOSYS as u32),
                arch,
            ),
        ];
        for filter in filters {
            let program: Result<seccompiler::BpfProgram, _> = match filter {
                Ok(f) => f
                    .try_into()
                    .map_err(|e: seccompiler::BackendError| e.to_string()),
                Err(e) => Err(e.to_string()),
            };
            let applied = program
                .and_then(|p| seccompiler::apply_filter_all_threads(&p).map_err(|e| e.to_string()));
            if let Err(e) = applied {
                return Some(format!(
                    "seccomp could not be set up ({e}): the lesson's system calls are not restricted"
                ));
            }
        }
        None
    }
}
