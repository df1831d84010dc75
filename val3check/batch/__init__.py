"""`val3check sim` on many cases: applications × arms × scenarios × cells × overrides, on all
cores or on a Dask cluster (docs/batch.md). It stands on simulation/ and reporting/, below cli.

- `sweep`      the sweep file (--sweep): read and checked, mistakes at their line and column,
               its paths inside its repository, its size limited;
- `globs`      globs expanded inside their roots, never through a link;
- `cases`      the cases: applications found (globs, folders, controller trees), each case
               carrying the files its run reads (`carry`: through the file gate, links as links);
- `worker`     one case run where it lands (`run_case`: simulation/case.py in a mirror of its
               files), its small picklable `CaseSummary`;
- `runner`     the child process that runs cases, and the watchdog that stops one over budget;
- `outputs`    the per-case report files (one function: a line per format);
- `executors`  child processes on this machine (-j N), Dask (--executor dask);
- `summary`    the summary in text, JSON, JUnit and an HTML index;
- `outdir`     --out-dir: where each file goes, nothing outside it;
- `progress`   cases done, failures, elapsed, estimate (on a terminal);
- `command`    the batch of `val3check sim`: options to cases to results to exit code.
"""
