"""flexbeam.model"""
