"""``python -m validation`` (run from the repository root)."""
from .cli import Main

raise SystemExit(Main())
