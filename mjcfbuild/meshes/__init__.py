"""Mesh files: reading every supported format and converting them into OBJ products."""
