"""flexbeam.methods"""
