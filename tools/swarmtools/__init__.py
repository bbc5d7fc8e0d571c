"""swarmtools"""
