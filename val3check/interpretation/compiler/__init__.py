"""The compiler of the virtual controller: VAL 3 programs to resumable Python generators
(program.py explains how)."""

from .program import compile_program
from .structures import Compiled, CompileError

__all__ = ["Compiled", "CompileError", "compile_program"]
