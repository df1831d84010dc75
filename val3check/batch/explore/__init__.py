"""`val3check sim --explore`: the failures that only some timings of the cell show
(docs/explore.md).

- `timings`   the times and delays of a scenario that vary, their ranges, a variant's text;
- `search`    which variants: boundaries of the nominal run first, then uniform draws (seeded);
- `shrink`    a failing variant moved back toward the nominal while it fails the same way;
- `findings`  the causes of failure of a run, grouped;
- `report`    the summary (text, JSON, JUnit, HTML index) and the reproducers' comments;
- `command`   the command: options to variants to runs (the batch's executors) to exit code.
"""
