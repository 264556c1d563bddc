"""Rule family lists (to be filled)."""
