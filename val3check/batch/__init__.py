"""`val3check sim` on many cases: applications × arms × scenarios × cells × overrides, on all
cores or on a Dask cluster (docs/batch.md). It stands on simulation/ and reporting/, below cli.

- `sweep`      the sweep file (--sweep): read and checked, mistakes at their line and column;
- `cases`      the cases: applications found (globs, folders, controller trees), each case
               carrying the bytes of the files its run reads;
- `worker`     one case run where it lands (`run_case`), its small picklable `CaseSummary`;
- `outputs`    the per-case report files (one function: a line per format);
- `executors`  serial, a process pool (-j N), Dask (--executor dask);
- `summary`    the summary in text, JSON, JUnit and an HTML index;
- `outdir`     --out-dir: where each file goes, nothing outside it;
- `progress`   cases done, failures, elapsed, estimate (on a terminal);
- `command`    the batch of `val3check sim`: options to cases to results to exit code.
"""
