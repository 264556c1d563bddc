"""Rule family objects (to be filled)."""
