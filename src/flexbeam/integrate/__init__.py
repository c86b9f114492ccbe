"""flexbeam.integrate"""
