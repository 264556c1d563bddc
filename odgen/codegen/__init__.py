"""Code generation: placement and hooks (options), a view-model, jinja2 templates."""
