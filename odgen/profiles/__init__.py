"""Device profiles odgen can generate descriptions for (`odgen profile ...`)."""
