"""Rule family pdo (to be filled)."""
