"""Rule family comm (to be filled)."""
