"""Rule family xml (to be filled)."""
