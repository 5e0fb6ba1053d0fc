"""archquake.dem"""
