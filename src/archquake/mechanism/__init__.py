"""archquake.mechanism"""
