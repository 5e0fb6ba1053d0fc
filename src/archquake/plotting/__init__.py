"""archquake.plotting"""
