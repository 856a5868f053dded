# Type hints of the package's native part (tools/python/Module.cpp), which editors cannot
# read from the shared object; the package's own API is annotated in __init__.py.
from typing import Any, Dict, List, Sequence, Tuple

version: str

class Solved:
    status: int
    json: str
    errors: str
    diagnostics: str
    diagnostics_text: str
    summary_html: str
    def plots(self) -> List[Dict[str, Any]]: ...
    def remarks(self) -> Dict[str, Dict[str, List[str]]]: ...

def check(source: str, is_text: bool, display: str) -> Dict[str, Any]: ...
def solve(
    token: int,
    source: str,
    is_text: bool,
    display: str,
    gearbox: str,
    jobs: int,
    time_limit: float,
    timings: bool,
    overrides: Sequence[Tuple[str, str]],
) -> Solved: ...
def cli(args: Sequence[str]) -> Tuple[int, str, str]: ...
def interrupt(token: int) -> None: ...
