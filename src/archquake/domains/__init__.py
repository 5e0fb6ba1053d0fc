"""archquake.domains"""
