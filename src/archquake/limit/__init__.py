"""archquake.limit"""
