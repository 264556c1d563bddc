"""Rule family header (to be filled)."""
