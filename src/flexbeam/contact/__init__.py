"""flexbeam.contact"""
