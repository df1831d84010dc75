import sys

if sys.argv[1:2] == ["lint"]:  # cli._short_lived, from the first import on (its passes cost ~4 ms)
    import gc

    gc.disable()

from .cli import main

sys.exit(main())
